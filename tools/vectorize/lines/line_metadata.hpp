// The metadata of a line package (tileformat::LineMetadata), from the
// settings, the plan and what the read pass found.
#pragma once

#include <cstdint>
#include <vector>

#include "io/vector_reader.hpp"
#include "lines/line_classes.hpp"
#include "lines/line_plan.hpp"
#include "lines/lines_settings.hpp"
#include "tileformat/metadata.hpp"

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
