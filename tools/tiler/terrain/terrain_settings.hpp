// Settings of `globe-tiler terrain`, filled by the command-line parser and
// read by the planner and builder (nothing here touches GDAL).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "kit/build_options.hpp"

namespace globe {

struct TerrainSettings : BuildOptions {
  int block_size = 257;             // samples per side, 2^k + 1
  std::optional<double> precision;  // height step in metres
  std::string resampling = "bilinear";
  std::optional<double> nodata;
  int lattice = 16;  // KPatch lattice (fixed in format v1)
};

}  // namespace globe
