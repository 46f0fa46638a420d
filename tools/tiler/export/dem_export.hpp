// `globe-tiler export TERRAIN --format terrarium|terrain-rgb` (docs/web.md
// "Terrarium and Terrain-RGB"): a terrain package as raster-DEM PNG tiles in
// web mercator XYZ, each pixel the package's height at its centre, bilinear
// between the samples of the block of that zoom (samples sit on tile edges,
// pixels are areas). A webmercator package keeps its tiles and zooms; a
// geodetic one is resampled: every web mercator tile over its bounds, at the
// zooms whose pixels are no finer than its samples, from the coarsest zoom
// whose samples are at least as fine as the pixels.
#pragma once

#include <cstdint>
#include <string>

#include "kit/progress.hpp"
#include "web/raster_dem.hpp"

namespace globe {

struct DemExportSettings {
  std::string input, output;
  web::DemEncoding encoding = web::DemEncoding::kTerrarium;
  int tile_size = 256;  // 256 or 512
  int threads = 1;
  bool force = false;
};

struct ExportSummary {
  uint64_t tiles = 0, bytes = 0;
  uint64_t pixels_without_data = 0;  // outside every block: written as 0 m
  int min_zoom = 0, max_zoom = 0;
  double seconds = 0;
};

ExportSummary export_raster_dem(const DemExportSettings& s, Progress& progress);

}  // namespace globe
