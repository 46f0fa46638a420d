// Line package planning (see line_plan.hpp).
#include "lines/line_plan.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "runtime/errors.hpp"

namespace globe {
namespace {

using tileformat::Bounds;
using tileformat::Tiling;

constexpr double kAntialiasPx = 1.0;
constexpr int kDefaultMaxZoomCap = 18;
constexpr int kPointsOnlyMaxZoom = 14;

}  // namespace

void LengthHistogram::add(double len) {
  if (!(len > 0)) return;
  const int bin = std::clamp(static_cast<int>(std::floor(4 * std::log2(len))) + kOffset, 0,
                             int(bins_.size()) - 1);
  ++bins_[bin];
  ++count_;
}

double LengthHistogram::median() const {
  uint64_t seen = 0;
  for (size_t b = 0; b < bins_.size(); ++b) {
    seen += bins_[b];
    if (2 * seen >= count_) return std::exp2((int(b) - kOffset + 0.5) / 4.0);
  }
  return 0;
}

LinePlan plan_lines(const LinesSettings& s, const VectorFrame& frame, const Bounds& extent,
                    const LengthHistogram& lengths, const LineClasses& classes) {
  LinePlan p;
  p.tiling = frame_tiling(frame, extent);
  p.area = frame_area(frame, p.tiling, s);
  p.min_zoom = s.min_zoom.value_or(0);
  if (s.max_zoom) {
    p.max_zoom = *s.max_zoom;
  } else if (lengths.count() == 0) {
    p.max_zoom = std::max(p.min_zoom, kPointsOnlyMaxZoom);
  } else {
    // The first zoom where the median segment spans 4 pixels: deeper zooms
    // would add no shape, only magnify (the viewer overzooms instead).
    const double median = lengths.median();
    p.max_zoom = p.min_zoom;
    while (p.max_zoom < kDefaultMaxZoomCap &&
           median < 4 * p.tiling.tile_size(p.max_zoom) / kLineTilePx)
      ++p.max_zoom;
  }
  if (p.min_zoom > p.max_zoom)
    throw UsageError("--min-zoom " + std::to_string(p.min_zoom) + " is above the max zoom " +
                     std::to_string(p.max_zoom));
  // Reach: the widest class (half width + casing) plus antialiasing, in
  // tile units, for a tile drawn at its nominal 256 px.
  const double units_per_px = s.extent / kLineTilePx;
  double crs_per_m = 1;
  if (frame.frame != TargetFrame::kProjected) {
    const XY lo = LineProjector::frame_to_lonlat(frame.frame, {extent.min_x, extent.min_y});
    const XY hi = LineProjector::frame_to_lonlat(frame.frame, {extent.max_x, extent.max_y});
    const double lat = std::min(85.0, std::max(std::abs(lo.y), std::abs(hi.y)));
    const double c = std::cos(lat * std::numbers::pi / 180);
    crs_per_m = frame.frame == TargetFrame::kWebMercator ? 1 / c : 1 / (111320.0 * c);
  } else {
    crs_per_m = 1 / frame.target->linear_units();
  }
  p.reach.assign(p.max_zoom + 1, 0);
  for (int z = p.min_zoom; z <= p.max_zoom; ++z) {
    const double units_per_crs = s.extent / p.tiling.tile_size(z);
    const double half = std::max(classes.max_half_px() * units_per_px,
                                 classes.max_half_m() * crs_per_m * units_per_crs);
    p.reach[z] =
        std::min<uint32_t>(static_cast<uint32_t>(std::ceil(half + kAntialiasPx * units_per_px)),
                           static_cast<uint32_t>(s.extent / 4));
  }
  return p;
}

}  // namespace globe
