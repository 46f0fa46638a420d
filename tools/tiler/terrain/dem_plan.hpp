// Planning a terrain build: opens every input once to resolve its CRS,
// nodata and extent, and derives the tiling, the zoom range, the height step
// and the areas (in the tiling CRS) that hold data. Throws InputError or
// UsageError with the file name and what to do.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "raster/raster_footprint.hpp"
#include "terrain/terrain_settings.hpp"
#include "tileformat/tiling.hpp"

namespace globe {

struct DemSource : RasterSource {
  std::optional<double> nodata;  // effective nodata value
  bool integer_type = false;
};

struct DemPlan : Footprint {  // tiling, data areas, resolution, zooms
  std::vector<DemSource> sources;
  int steps = 256;      // block size - 1
  double step_m = 1.0;  // quantization step
  int32_t fill_q = 0;   // height (quanta) for holes at block corners
  // Whether the warp may work in single precision (twice as fast in GDAL's
  // kernel): the inputs' values are exact in it and its rounding stays far
  // below the step (see plan_terrain).
  bool warp_single = false;
};

DemPlan plan_terrain(const TerrainSettings& settings);

}  // namespace globe
