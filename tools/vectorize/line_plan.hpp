// Planning of a line package (docs/lines.md "Tiling and zooms"): the frame
// features are projected into and the tiling (before reading), then, from
// what the read pass gathered, the area, the zoom range and each zoom's
// reach.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "line_classes.hpp"
#include "line_projector.hpp"
#include "lines_settings.hpp"
#include "spatial_ref.hpp"
#include "tileformat/tiling.hpp"

namespace globe {

// Nominal display size of a tile in pixels (docs/lines.md).
inline constexpr double kLineTilePx = 256.0;

struct LineFrame {
  TargetFrame frame = TargetFrame::kWebMercator;
  // kProjected: the tiling CRS (--like, --t_srs, or the first input's CRS,
  // filled in by the builder once the inputs are open).
  std::optional<SpatialRef> target;
  // Known before reading for --like and the global schemes; a local tiling
  // is placed on the data by plan_lines().
  std::optional<tileformat::Tiling> tiling;
};

// From --like, --tiling and --t_srs; throws UsageError for conflicting ones.
LineFrame choose_line_frame(const LinesSettings& s);

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
LinePlan plan_lines(const LinesSettings& s, const LineFrame& frame,
                    const tileformat::Bounds& extent, const LengthHistogram& lengths,
                    const LineClasses& classes);

}  // namespace globe
