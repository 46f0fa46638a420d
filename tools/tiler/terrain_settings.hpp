// Settings of `globe-tiler terrain`, filled by the command-line parser and
// read by the planner and builder (nothing here touches GDAL).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "progress.hpp"

namespace globe {

struct TerrainSettings {
  std::vector<std::string> inputs;
  std::string output;
  std::string tiling = "webmercator";  // webmercator | geodetic | local
  std::string t_srs;                   // local tiling only
  std::string s_srs;                   // overrides/assigns the inputs' CRS
  std::optional<int> min_zoom, max_zoom;
  std::optional<std::vector<double>> bbox;  // lon/lat: west,south,east,north
  int block_size = 257;                     // samples per side, 2^k + 1
  std::optional<double> precision;          // height step in metres
  std::string resampling = "bilinear";
  std::optional<double> nodata;
  int threads = 0;  // 0 = all cores
  bool force = false;
  ProgressMode progress = ProgressMode::kAuto;
  int lattice = 16;          // KPatch lattice (fixed in format v1)
  std::string command_line;  // recorded in metadata (without -j/-q/--progress)
};

}  // namespace globe
