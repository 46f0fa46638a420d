// Line package planning (see line_plan.hpp).
#include "line_plan.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "errors.hpp"
#include "tileformat/package.hpp"

namespace globe {
namespace {

using tileformat::Bounds;
using tileformat::Tiling;

constexpr double kAntialiasPx = 1.0;
constexpr int kDefaultMaxZoomCap = 18;
constexpr int kPointsOnlyMaxZoom = 14;

}  // namespace

LineFrame choose_line_frame(const LinesSettings& s) {
  LineFrame f;
  if (!s.like.empty()) {
    tileformat::PackageReader like(s.like);
    f.tiling = Tiling::from_metadata(like.metadata());
    if (f.tiling->scheme == tileformat::Scheme::kLocal) {
      f.frame = TargetFrame::kProjected;
      f.target = SpatialRef::from_wkt(f.tiling->crs, s.like);
    } else {
      f.frame = f.tiling->scheme == tileformat::Scheme::kGeodetic ? TargetFrame::kGeodetic
                                                                  : TargetFrame::kWebMercator;
    }
    return f;
  }
  if (s.tiling == tileformat::Scheme::kWebMercator) {
    f.frame = TargetFrame::kWebMercator;
    f.tiling = Tiling::webmercator();
  } else if (s.tiling == tileformat::Scheme::kGeodetic) {
    f.frame = TargetFrame::kGeodetic;
    f.tiling = Tiling::geodetic();
  } else {
    f.frame = TargetFrame::kProjected;
    if (!s.t_srs.empty()) f.target = SpatialRef::from_user_input(s.t_srs, "--t_srs");
  }
  if (!s.t_srs.empty() && f.frame != TargetFrame::kProjected)
    throw UsageError("--t_srs applies to --tiling local only");
  return f;
}

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

LinePlan plan_lines(const LinesSettings& s, const LineFrame& frame, const Bounds& extent,
                    const LengthHistogram& lengths, const LineClasses& classes) {
  LinePlan p;
  if (frame.tiling) {
    p.tiling = *frame.tiling;
  } else {
    const double span = std::max({extent.width(), extent.height(), 1e-9});
    const double root = std::exp2(std::ceil(std::log2(span)));
    p.tiling = Tiling::local(frame.target->wkt2(), extent.min_x, extent.max_y, root);
  }
  p.area = p.tiling.extent();
  if (s.bbox) {
    const auto& b = *s.bbox;
    Bounds box;
    if (frame.frame == TargetFrame::kProjected) {
      CoordTransform t(SpatialRef::from_user_input("EPSG:4326", "--bbox"), *frame.target);
      if (!t.transform_bounds({b[0], b[1], b[2], b[3]}, box))
        throw UsageError("--bbox cannot be expressed in the tiling CRS");
    } else {
      const XY lo = LineProjector::lonlat_to_frame(frame.frame, {b[0], b[1]});
      const XY hi = LineProjector::lonlat_to_frame(frame.frame, {b[2], b[3]});
      box = {lo.x, lo.y, hi.x, hi.y};
    }
    p.area = {std::max(p.area.min_x, box.min_x), std::max(p.area.min_y, box.min_y),
              std::min(p.area.max_x, box.max_x), std::min(p.area.max_y, box.max_y)};
  }
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
