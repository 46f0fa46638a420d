// The metadata of a line package (tileformat::LineMetadata), from the
// settings, the plan and what the read pass found.
#pragma once

#include <cstdint>
#include <vector>

#include "line_classes.hpp"
#include "line_plan.hpp"
#include "lines_settings.hpp"
#include "tileformat/metadata.hpp"
#include "vector_reader.hpp"

namespace globe {

struct LineFacts {
  tileformat::Bounds extent{1e300, 1e300, -1e300, -1e300};  // the data, tiling CRS
  uint64_t features = 0;                                    // kept
  std::vector<VectorLayerInfo> layers;
  std::vector<uint64_t> layer_features;  // kept, per layer
};

tileformat::LineMetadata line_metadata(const LinesSettings& s, const VectorFrame& frame,
                                       const LinePlan& plan, const LineClasses& classes,
                                       const LineFacts& facts);

}  // namespace globe
