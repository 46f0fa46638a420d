// Planning of a line package (docs/lines.md "Tiling and zooms"): from what
// the read pass gathered, the tiling (vector_frame.hpp), the area, the zoom
// range and each zoom's reach.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "io/vector_frame.hpp"
#include "lines/line_classes.hpp"
#include "lines/line_projector.hpp"
#include "lines/lines_settings.hpp"
#include "tileformat/tiling.hpp"

namespace globe {

// Nominal display size of a tile in pixels (docs/lines.md).
inline constexpr double kLineTilePx = 256.0;

// Segment lengths on a log scale (quarter octaves), for the median.
class LengthHistogram {
 public:
  void add(double len);
  uint64_t count() const { return count_; }
  double median() const;

 private:
  static constexpr int kOffset = 200;
  std::array<uint64_t, 401> bins_{};
  uint64_t count_ = 0;
};

struct LinePlan {
  tileformat::Tiling tiling;
  tileformat::Bounds area;  // tiling CRS: the tiling's extent within --bbox
  int min_zoom = 0, max_zoom = 0;
  std::vector<uint32_t> reach;  // per zoom, in tile units: how far a line's drawing reaches
};

// `extent`: the data in the tiling CRS. Default max zoom: the first where the
// median segment spans 4 pixels (14 for points only, at most 18). Throws
// UsageError for a --bbox outside the tiling CRS or --min-zoom above the max.
LinePlan plan_lines(const LinesSettings& s, const VectorFrame& frame,
                    const tileformat::Bounds& extent, const LengthHistogram& lengths,
                    const LineClasses& classes);

}  // namespace globe
