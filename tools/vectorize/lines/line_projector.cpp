// Projection into the tiling CRS (see line_projector.hpp).
#include "lines/line_projector.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "tileformat/tiling.hpp"

namespace globe {
namespace {

constexpr double kMaxMercatorLat = 85.05112877980659;
constexpr double kEarthRadius = 6378137.0;

}  // namespace

LineProjector::LineProjector(TargetFrame frame, const SpatialRef& source, const SpatialRef* target)
    : frame_(frame) {
  if (frame == TargetFrame::kProjected)
    to_frame_ = std::make_unique<CoordTransform>(source, *target);
  else
    to_frame_ = std::make_unique<CoordTransform>(
        source, SpatialRef::from_user_input("EPSG:4326", "longitude/latitude"));
}

XY LineProjector::lonlat_to_frame(TargetFrame frame, XY p) {
  if (frame != TargetFrame::kWebMercator) return p;
  const double lat = std::clamp(p.y, -kMaxMercatorLat, kMaxMercatorLat) * std::numbers::pi / 180;
  return {kEarthRadius * p.x * std::numbers::pi / 180,
          kEarthRadius * std::log(std::tan(std::numbers::pi / 4 + lat / 2))};
}

XY LineProjector::frame_to_lonlat(TargetFrame frame, XY p) {
  if (frame != TargetFrame::kWebMercator) return p;
  return {p.x / kEarthRadius * 180 / std::numbers::pi,
          (2 * std::atan(std::exp(p.y / kEarthRadius)) - std::numbers::pi / 2) * 180 /
              std::numbers::pi};
}

namespace {

// Longitude/latitude that exist: |lat| <= 90; longitudes wrap, but only
// within one turn either side (as --bbox), beyond is a broken coordinate.
bool on_the_globe(const std::vector<XY>& pts) {
  return std::all_of(pts.begin(), pts.end(),
                     [](XY p) { return std::abs(p.y) <= 90.0 && std::abs(p.x) <= 540.0; });
}

}  // namespace

bool LineProjector::transform(std::vector<XY>& pts) const {
  std::vector<double> x(pts.size()), y(pts.size());
  for (size_t i = 0; i < pts.size(); ++i) {
    x[i] = pts[i].x;
    y[i] = pts[i].y;
  }
  if (!to_frame_->transform(x, y)) return false;
  for (size_t i = 0; i < pts.size(); ++i)
    pts[i] = {x[i], y[i]};
  return true;
}

void LineProjector::project_lines(const std::vector<std::vector<XY>>& in,
                                  std::vector<std::vector<XY>>& out,
                                  ProjectionCounts& counts) const {
  for (const std::vector<XY>& src : in) {
    std::vector<XY> part = src;
    PartStatus st = clean_part(part);
    if (st == PartStatus::kOk &&
        (!transform(part) || (frame_ != TargetFrame::kProjected && !on_the_globe(part)))) {
      ++counts.failed_parts;
      continue;
    }
    if (st == PartStatus::kOk) st = clean_part(part);
    if (st != PartStatus::kOk) {
      ++(st == PartStatus::kNonFinite ? counts.nonfinite_parts : counts.degenerate_parts);
      continue;
    }
    if (frame_ == TargetFrame::kProjected) {
      out.push_back(std::move(part));
      continue;
    }
    auto pieces = split_antimeridian(part);
    counts.antimeridian_cuts += pieces.size() - 1;
    for (auto& piece : pieces) {
      for (XY& p : piece)
        p = lonlat_to_frame(frame_, p);
      if (clean_part(piece) == PartStatus::kOk) out.push_back(std::move(piece));
    }
  }
}

bool LineProjector::transform_ring(std::vector<XY>& ring) const {
  for (const XY& p : ring)
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return false;
  if (!transform(ring)) return false;
  for (const XY& p : ring)
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return false;
  return frame_ == TargetFrame::kProjected || on_the_globe(ring);
}

bool LineProjector::project_point(XY in, XY& out) const {
  std::vector<XY> p{in};
  if (!std::isfinite(in.x) || !std::isfinite(in.y) || !transform(p)) return false;
  if (!std::isfinite(p[0].x) || !std::isfinite(p[0].y)) return false;
  if (frame_ != TargetFrame::kProjected && !on_the_globe(p)) return false;
  if (frame_ != TargetFrame::kProjected)
    p[0] = lonlat_to_frame(frame_, split_antimeridian(p).front().front());  // wraps longitude
  out = p[0];
  return true;
}

}  // namespace globe
