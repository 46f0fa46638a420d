// What the slope and sky-view modes' built-in ramps span on this data
// (docs/viewer.md "Readable by default"): on a coarse grid the slopes
// between samples are gentle and the sky is open almost everywhere, so the
// fixed ramps (0..45 degrees, sky-view 0.65..1) come out pale or white. The
// ramps are stretched so that the data's 95th-percentile slope and its
// 5th-percentile sky-view factor read at the middle of the ramp; detailed
// data, whose values already reach there, keeps the fixed ramps. Measured
// once at startup from the package's finest zoom (the data's own values, not
// the drawn LOD's, so colours do not change with distance): up to 16 blocks
// spread over it. A --colormap file keeps its own values.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <utility>

#include "tileformat/tile_id.hpp"

namespace globe::viewer {

struct DataRanges {
  static constexpr double kSlopeTopDeg = 45;  // the fixed slope ramp's top
  static constexpr double kSkyLow = 0.65;     // the fixed sky-view ramp's black
  double slope_top_deg = kSlopeTopDeg;        // 2 .. 45
  double sky_low = kSkyLow;                   // 0.65 .. 0.99
  double slope_p95_deg = -1, sky_p5 = -1;     // as measured (-1: none)
};

// spacing_m: ground metres between a block's samples (east, south).
// analysis_path: the analysis package drawn, whose sky-view layer is read.
DataRanges measure_data_ranges(
    const std::string& terrain_path, const std::optional<std::string>& analysis_path,
    const std::function<std::pair<double, double>(tileformat::TileId)>& spacing_m);

}  // namespace globe::viewer
