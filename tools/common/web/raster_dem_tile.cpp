// One raster-DEM tile of a terrain package (see raster_dem_tile.hpp).
#include "raster_dem_tile.hpp"

#include <algorithm>
#include <cmath>

#include "png_codec.hpp"

namespace globe::web {
namespace {

// libpng adaptive filters at deflate 6: on the 4096² synthetic DEM 28.0 MB in 8.1 s,
// against 31.6 MB in 5.1 s at 4 and 37.7 MB in 3.3 s at 1 (bench/export.sh).
constexpr int kPngEffort = 6;

}  // namespace

int raster_dem_source_zoom(const TerrainPackage& package, int z, int tile_size) {
  if (package.tiling.scheme == tileformat::Scheme::kWebMercator)
    return std::clamp(z, package.min_zoom, package.max_zoom);
  // Geodetic zoom g has samples 180 / (2^g steps) degrees apart, web mercator
  // zoom z pixels 360 / (2^z size) apart at the equator.
  const double finer = std::log2(2.0 * (package.block_size - 1) / tile_size);
  return std::clamp(static_cast<int>(std::ceil(z - finer - 1e-9)), package.min_zoom,
                    package.max_zoom);
}

std::vector<uint8_t> raster_dem_tile(TerrainSampler& sampler, const tileformat::Tiling& tiling,
                                     int z, uint32_t x, uint32_t y, int size, int source_zoom,
                                     DemEncoding encoding, uint64_t* without_data) {
  const bool mercator = tiling.scheme == tileformat::Scheme::kWebMercator;
  std::vector<uint8_t> rgb(size_t(size) * size * 3);
  uint64_t missing = 0;
  for (int j = 0; j < size; ++j)
    for (int k = 0; k < size; ++k) {
      const MercatorPoint p = pixel_centre(z, x, y, size, k, j);
      double cx = p.x, cy = p.y;
      if (!mercator) mercator_to_lonlat(p, cx, cy);
      const std::optional<double> h = sampler.height(cx, cy, source_zoom);
      missing += !h;
      encode_dem_pixel(h.value_or(0.0), encoding, &rgb[(size_t(j) * size + k) * 3]);
    }
  if (missing == uint64_t(size) * size) return {};  // a tile with no data at all is left out
  if (without_data) *without_data += missing;
  return encode_png(rgb.data(), size, size, 3, kPngEffort);
}

}  // namespace globe::web
