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

// PNG efforts (png_codec.hpp). Measured on the 4096² synthetic DEM's
// Terrarium tiles of zoom 14: adaptive filters at deflate 6, 23.2 KB a tile
// in 10.5 ms (the exports: files are written once, fetched often); Paeth and
// run-length deflate, 31.9 KB in 1.8 ms (the server, which cuts a tile while
// its client waits). zlib's entropy coding alone costs 1.3 ms a tile.
constexpr int kPngSmall = 6, kPngFast = 1;

// The PNG, or empty bytes where no block lies under any pixel;
// `without_data` counts the pixels without a block (written as 0 m).
std::vector<uint8_t> raster_dem_tile(TerrainSampler& sampler, const tileformat::Tiling& tiling,
                                     int z, uint32_t x, uint32_t y, int size, int source_zoom,
                                     DemEncoding encoding, uint64_t* without_data = nullptr,
                                     int png_effort = kPngSmall);

}  // namespace globe::web
