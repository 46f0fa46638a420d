// Settings of `globe-vectorize lines`, filled by the command-line parser and
// read by the builder (nothing here touches OGR).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "kit/build_options.hpp"
#include "labels/label_candidates.hpp"

namespace globe {

struct LinesSettings : BuildOptions {
  std::string like;                 // package whose tiling to adopt
  std::vector<std::string> layers;  // --layer (repeatable)
  std::string where;
  std::string class_field, class_map;
  std::vector<std::string> styles;  // --style CLASS:key=value,...
  int cluster_grid = 32;
  int extent = 4096;
  double simplify_px = 0.25;
  size_t memory_mb = 256;
  LabelOptions labels;  // --label-field, --priority-field (docs/labels.md)
};

}  // namespace globe
