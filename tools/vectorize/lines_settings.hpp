// Settings of `globe-vectorize lines`, filled by the command-line parser and
// read by the builder (nothing here touches OGR).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "progress.hpp"

namespace globe {

struct LinesSettings {
  std::vector<std::string> inputs;
  std::string output;
  std::string tiling = "webmercator";  // webmercator | geodetic | local
  std::string like;                    // package whose tiling to adopt
  std::string t_srs;                   // local tiling CRS
  std::string s_srs;                   // assigned input CRS
  std::vector<std::string> layers;     // --layer (repeatable)
  std::string where;
  std::optional<int> min_zoom, max_zoom;
  std::optional<std::vector<double>> bbox;  // lon/lat: west,south,east,north
  std::string class_field, class_map;
  std::vector<std::string> styles;  // --style CLASS:key=value,...
  int cluster_grid = 32;
  int extent = 4096;
  double simplify_px = 0.25;
  int threads = 0;
  size_t memory_mb = 1024;
  bool force = false;
  ProgressMode progress = ProgressMode::kAuto;
  std::string command_line;  // recorded in metadata (without -j/-q/--progress/--force)
};

}  // namespace globe
