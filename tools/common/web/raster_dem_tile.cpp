// One raster-DEM tile of a terrain package (see raster_dem_tile.hpp).
#include "web/raster_dem_tile.hpp"

#include <algorithm>
#include <cmath>

#include "runtime/png_codec.hpp"

namespace globe::web {
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
                                     DemEncoding encoding, uint64_t* without_data, int png_effort) {
  // Web mercator x and y of the pixel centres; a geodetic package's longitude
  // depends on x only and its latitude on y only, so the grid stays separable.
  const bool mercator = tiling.scheme == tileformat::Scheme::kWebMercator;
  std::vector<double> xs(size_t(size), 0.0), ys(size_t(size), 0.0);
  for (int k = 0; k < size; ++k) {
    const MercatorPoint p = pixel_centre(z, x, y, size, k, k);
    xs[size_t(k)] = p.x, ys[size_t(k)] = p.y;
    if (!mercator) mercator_to_lonlat(p, xs[size_t(k)], ys[size_t(k)]);
  }
  std::vector<double> heights;
  sampler.heights(xs, ys, source_zoom, heights);
  std::vector<uint8_t> rgb(size_t(size) * size * 3);
  uint64_t missing = 0;
  for (size_t p = 0; p < heights.size(); ++p) {
    missing += std::isnan(heights[p]);
    encode_dem_pixel(std::isnan(heights[p]) ? 0.0 : heights[p], encoding, &rgb[p * 3]);
  }
  if (missing == uint64_t(size) * size) return {};  // a tile with no data at all is left out
  if (without_data) *without_data += missing;
  return encode_png(rgb.data(), size, size, 3, png_effort,
                    png_effort == kPngFast ? PngFilter::kAdaptive : PngFilter::kUp);
}

}  // namespace globe::web
