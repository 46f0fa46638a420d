// Plane geometry of the line pipeline (see line_geometry.hpp).
#include "lines/line_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "tileformat/line_clusters.hpp"

namespace globe {
namespace {

double wrap_lon(double lon) {
  if (lon >= -180 && lon <= 180) return lon;
  lon = std::fmod(lon + 180.0, 360.0);
  if (lon < 0) lon += 360.0;
  return lon - 180.0;
}

}  // namespace

PartStatus clean_part(std::vector<XY>& part) {
  for (const XY& p : part)
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return PartStatus::kNonFinite;
  part.erase(std::unique(part.begin(), part.end()), part.end());
  return part.size() >= 2 ? PartStatus::kOk : PartStatus::kDegenerate;
}

double segment_distance(XY p, XY a, XY b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / len2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
}

std::vector<XY> douglas_peucker(std::span<const XY> in, double tolerance) {
  if (in.size() <= 2 || tolerance <= 0) return {in.begin(), in.end()};
  std::vector<uint8_t> keep(in.size(), 0);
  keep.front() = keep.back() = 1;
  std::vector<std::pair<size_t, size_t>> stack{{0, in.size() - 1}};
  while (!stack.empty()) {
    const auto [first, last] = stack.back();
    stack.pop_back();
    double worst = -1;
    size_t at = first;
    for (size_t i = first + 1; i < last; ++i) {
      const double d = segment_distance(in[i], in[first], in[last]);
      if (d > worst) {
        worst = d;
        at = i;
      }
    }
    if (worst > tolerance) {
      keep[at] = 1;
      stack.push_back({first, at});
      stack.push_back({at, last});
    }
  }
  std::vector<XY> out;
  for (size_t i = 0; i < in.size(); ++i)
    if (keep[i]) out.push_back(in[i]);
  return out;
}

bool clip_segment(XY& a, XY& b, const tileformat::Bounds& box, double* t0_out, double* t1_out) {
  double t0, t1;
  if (!tileformat::clip_parameters(a.x, a.y, b.x, b.y, box.min_x, box.min_y, box.max_x, box.max_y,
                                   t0, t1))
    return false;
  const XY start = a;
  const double dx = b.x - a.x, dy = b.y - a.y;
  if (t0 > 0) a = {start.x + t0 * dx, start.y + t0 * dy};
  if (t1 < 1) b = {start.x + t1 * dx, start.y + t1 * dy};
  if (t0_out) *t0_out = t0;
  if (t1_out) *t1_out = t1;
  return true;
}

std::vector<std::vector<XY>> split_antimeridian(std::span<const XY> lonlat) {
  std::vector<std::vector<XY>> out(1);
  for (size_t i = 0; i < lonlat.size(); ++i) {
    const XY p{wrap_lon(lonlat[i].x), lonlat[i].y};
    if (!out.back().empty()) {
      const XY q = out.back().back();
      const double d = p.x - q.x;
      if (std::abs(d) > 180) {
        // Unwrap p next to q, find where the segment meets +-180, cut there.
        const double edge = d < 0 ? 180.0 : -180.0;
        const double px = p.x + (d < 0 ? 360.0 : -360.0);
        const double t = (edge - q.x) / (px - q.x);
        const double lat = q.y + t * (p.y - q.y);
        out.back().push_back({edge, lat});
        out.push_back({{-edge, lat}});
      }
    }
    out.back().push_back(p);
  }
  return out;
}

}  // namespace globe
