// One raster-DEM tile (docs/web.md "Terrarium and Terrain-RGB") of a terrain
// package, for the export and the server: web mercator XYZ tile z/x/y of
// size x size pixels, each the package's height at the pixel's centre,
// bilinear between the samples of the blocks of `source_zoom` (a geodetic
// package is resampled), PNG-coded.
#pragma once

#include <cstdint>
#include <vector>

#include "runtime/terrain_package.hpp"
#include "web/raster_dem.hpp"
#include "web/terrain_sampler.hpp"

namespace globe::web {

// The package zoom whose samples a web mercator tile of zoom z is drawn from:
// a webmercator package's own (clamped to its zooms), for a geodetic one the
// coarsest whose samples are at least as fine as the pixels.
int raster_dem_source_zoom(const TerrainPackage& package, int z, int tile_size);

// PNG efforts (png_codec.hpp), measured side by side (bench/README.md
// "Raster-DEM PNG"). The exports (files written once, fetched often): every
// row predicted from the one above, deflate level 4 — against libpng's
// adaptive filters at level 6, 2.7-3.1x faster, 7 % smaller on a global 5'
// relief grid and 6 % larger on the 10 m synthetic DEM. The server, which
// cuts a tile while its client waits: Paeth and run-length deflate (effort 1).
constexpr int kPngSmall = 4, kPngFast = 1;

// The PNG, or empty bytes where no block lies under any pixel;
// `without_data` counts the pixels without a block (written as 0 m).
std::vector<uint8_t> raster_dem_tile(TerrainSampler& sampler, const tileformat::Tiling& tiling,
                                     int z, uint32_t x, uint32_t y, int size, int source_zoom,
                                     DemEncoding encoding, uint64_t* without_data = nullptr,
                                     int png_effort = kPngSmall);

}  // namespace globe::web
