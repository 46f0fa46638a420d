// Settings of `globe-vectorize points`, filled by the command-line parser and
// read by the builder (nothing here touches OGR).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "kit/build_options.hpp"
#include "tileformat/metadata.hpp"

namespace globe {

// Whether negative values are refused (pies and stacked bars show shares) or
// kept (the package is marked signed; bars and columns only).
enum class ValueSign { kNonNegative, kSigned };

struct PointsSettings : BuildOptions {
  std::string like;                 // package whose tiling to adopt
  std::vector<std::string> layers;  // --layer (repeatable)
  std::string where;
  std::vector<std::string> fields;                        // --fields: the chart's values
  std::string label_field;                                // --label-field
  std::string priority_field;                             // --priority-field
  std::optional<std::pair<std::string, std::string>> xy;  // --xy LONCOL,LATCOL (CSV)
  tileformat::PointAggregate aggregate = tileformat::PointAggregate::kSum;
  ValueSign sign = ValueSign::kNonNegative;
  double merge_px = 40;      // places closer than this at a zoom become one
  double chart_max_px = 48;  // the largest chart the cluster grids allow for
  int cluster_grid = 16;
  int extent = 4096;
  size_t memory_mb = 64;  // --memory-mb: for sorting places (the rest spills to disk)
};

}  // namespace globe
