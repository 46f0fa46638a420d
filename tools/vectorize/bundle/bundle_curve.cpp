// Bundle smoothing (see bundle_curve.hpp).
#include "bundle/bundle_curve.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace globe {

namespace {

constexpr int kMinSamplesPerSpan = 4, kMaxSamplesPerSpan = 64;

// The expanded control sequence: sharp points three times.
struct Expanded {
  std::vector<XY> p;
  std::vector<uint32_t> source;  // the polyline vertex of each
};

double dist(XY a, XY b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}

Expanded expand(std::span<const XY> poly, const ControlPoints& c) {
  Expanded e;
  const size_t last = c.index.size() - 1;
  // The tangent point of end k (toward control point `toward`), if any.
  auto tangent_point = [&](size_t k, size_t toward, XY t, double sign) {
    if (c.sharp[k] || (t.x == 0 && t.y == 0)) return;
    const XY p = poly[c.index[k]];
    const double d = dist(p, poly[c.index[toward]]) / 3 * sign;
    e.p.push_back({p.x + d * t.x, p.y + d * t.y});
    e.source.push_back(c.index[k]);
  };
  for (size_t k = 0; k <= last; ++k) {
    if (k == last && last > 0) tangent_point(last, last - 1, c.end_tangent, -1);
    for (int m = 0; m < (c.sharp[k] ? 3 : 1); ++m) {
      e.p.push_back(poly[c.index[k]]);
      e.source.push_back(c.index[k]);
    }
    if (k == 0 && last > 0) tangent_point(0, 1, c.start_tangent, 1);
  }
  return e;
}

// A clamped uniform B-spline of degree `p` over n control points: knot i.
double knot(int i, int n, int p) {
  return std::clamp(i - p, 0, n - p);
}

// De Boor's algorithm on span s (knots [s, s+1) in the clamped numbering).
XY de_boor(const std::vector<XY>& ctrl, int s, double u, int p) {
  const int n = static_cast<int>(ctrl.size());
  XY d[4];
  for (int j = 0; j <= p; ++j)
    d[j] = ctrl[size_t(j + s - p)];
  for (int r = 1; r <= p; ++r)
    for (int j = p; j >= r; --j) {
      const double lo = knot(j + s - p, n, p), hi = knot(j + 1 + s - r, n, p);
      const double a = hi > lo ? (u - lo) / (hi - lo) : 0;
      d[j] = {(1 - a) * d[j - 1].x + a * d[j].x, (1 - a) * d[j - 1].y + a * d[j].y};
    }
  return d[p];
}

// Calls visit(span, sample point) for the curve of `e` sampled about every
// `step`; the first point is visited with span -1.
template <typename Visit>
void sample_curve(const Expanded& e, double step, Visit&& visit) {
  const int n = static_cast<int>(e.p.size());
  const int p = std::min(3, n - 1);
  visit(-1, e.p.front());
  for (int s = p; s < n; ++s) {
    const double lo = knot(s, n, p), hi = knot(s + 1, n, p);
    if (!(hi > lo)) continue;
    double legs = 0;
    for (int j = s - p; j < s; ++j)
      legs += dist(e.p[size_t(j)], e.p[size_t(j + 1)]);
    // A span over one polyline segment (sharp neighbours) is that segment:
    // its end is all it needs.
    const bool on_segment = e.source[size_t(s)] - e.source[size_t(s - p)] <= 1;
    const int count =
        on_segment
            ? 1
            : static_cast<int>(std::clamp(std::ceil(legs / std::max(step, 1e-300)),
                                          double(kMinSamplesPerSpan), double(kMaxSamplesPerSpan)));
    for (int k = 1; k <= count; ++k)
      visit(s,
            k == count && s == n - 1 ? e.p.back() : de_boor(e.p, s, lo + (hi - lo) * k / count, p));
  }
}

// The vertex of poly strictly between a and b farthest from chord ab.
uint32_t farthest_between(std::span<const XY> poly, uint32_t a, uint32_t b) {
  uint32_t best = a + 1;
  double best_d = -1;
  for (uint32_t i = a + 1; i < b; ++i) {
    const double d = segment_distance(poly[i], poly[a], poly[b]);
    if (d > best_d) best = i, best_d = d;
  }
  return best;
}

// Refines `c` until its curve stays within `tolerance` of `poly`. A span's
// curve is checked against the polyline between the vertices of its control
// points (its support: local, so the cost follows the vertex count). A
// sample out of the corridor refines the control gap holding its nearest
// segment; if that gap is already exact (neighbouring sharp vertices), every
// gap of the span's support. Each round changes at least one gap, and a
// span of sharp neighbours is a polyline segment, so the rounds end.
void refine(std::span<const XY> poly, ControlPoints& c, double tolerance, double step) {
  auto exact_gap = [&](size_t k) {
    return c.index[k + 1] - c.index[k] == 1 && c.sharp[k] && c.sharp[k + 1];
  };
  auto gap_of = [&](uint32_t segment) {
    const auto it = std::upper_bound(c.index.begin(), c.index.end(), segment);
    return static_cast<size_t>(it - c.index.begin()) - 1;
  };
  for (;;) {
    const Expanded e = expand(poly, c);
    const int n = static_cast<int>(e.p.size());
    const int p = std::min(3, n - 1);
    std::vector<size_t> gaps;  // control gaps (index[k]..index[k+1]) to refine
    sample_curve(e, std::min(step, tolerance), [&](int s, XY q) {
      if (s < 0) return;
      const uint32_t lo = e.source[size_t(s - p)], hi = e.source[size_t(s)];
      if (hi == lo) return;  // a point: the curve is there
      double best = 1e300;
      uint32_t nearest = lo;
      for (uint32_t i = lo; i < hi; ++i) {
        const double d = segment_distance(q, poly[i], poly[i + 1]);
        if (d < best) best = d, nearest = i;
      }
      if (best <= tolerance) return;
      const size_t k = gap_of(nearest);
      if (!exact_gap(k)) {
        gaps.push_back(k);
        return;
      }
      for (size_t j = gap_of(lo); j < c.index.size() - 1 && c.index[j] < hi; ++j)
        if (!exact_gap(j)) gaps.push_back(j);
    });
    if (gaps.empty()) return;
    std::sort(gaps.begin(), gaps.end());
    gaps.erase(std::unique(gaps.begin(), gaps.end()), gaps.end());
    ControlPoints next;
    next.start_tangent = c.start_tangent;
    next.end_tangent = c.end_tangent;
    std::vector<uint8_t> sharpen(c.index.size(), 0);
    std::vector<uint32_t> insert(c.index.size(), 0);  // vertex after index[k] (0: none)
    for (size_t k : gaps) {
      const uint32_t a = c.index[k], b = c.index[k + 1];
      if (b - a > 1)
        insert[k] = farthest_between(poly, a, b);
      else
        sharpen[k] = sharpen[k + 1] = 1;
    }
    for (size_t k = 0; k < c.index.size(); ++k) {
      next.index.push_back(c.index[k]);
      next.sharp.push_back(c.sharp[k] || sharpen[k]);
      if (insert[k]) {
        next.index.push_back(insert[k]);
        next.sharp.push_back(0);
      }
    }
    c = std::move(next);
  }
}

}  // namespace

std::vector<XY> evaluate_curve(std::span<const XY> poly, const ControlPoints& controls,
                               double step) {
  std::vector<XY> out;
  sample_curve(expand(poly, controls), step, [&](int, XY q) {
    if (out.empty() || !(out.back() == q)) out.push_back(q);
  });
  return out;
}

std::vector<CurveLevel> smooth_bundle(std::span<const XY> poly, int min_zoom, int max_zoom,
                                      std::span<const double> tolerance,
                                      std::span<const double> step, XY start_tangent,
                                      XY end_tangent) {
  std::vector<CurveLevel> levels;
  if (poly.size() < 2) return levels;
  ControlPoints c;
  c.index = {0, static_cast<uint32_t>(poly.size() - 1)};
  c.sharp = {0, 0};
  c.start_tangent = start_tangent;
  c.end_tangent = end_tangent;
  ControlPoints level_controls;
  int level_finest = -1;
  auto close_level = [&] {
    if (level_finest < 0) return;
    levels.back().curve = evaluate_curve(poly, level_controls, step[size_t(level_finest)]);
  };
  for (int z = min_zoom; z <= max_zoom; ++z) {
    const bool exact =
        std::all_of(c.sharp.begin(), c.sharp.end(), [](uint8_t s) { return s != 0; }) &&
        c.index.size() == poly.size();
    if (!exact) refine(poly, c, tolerance[size_t(z)], step[size_t(z)]);
    if (levels.empty() || !(c == level_controls)) {
      close_level();
      levels.push_back({});
      level_controls = c;
    }
    levels.back().zooms |= 1u << z;
    level_finest = z;
  }
  close_level();
  return levels;
}

namespace {

// The unit direction from a polyline's first point toward its point a
// quarter of its length along ({0, 0} for a polyline of no length).
XY leg_direction(std::span<const XY> poly) {
  double total = 0;
  for (size_t i = 1; i < poly.size(); ++i)
    total += dist(poly[i - 1], poly[i]);
  if (!(total > 0)) return {0, 0};
  double left = total / 4;
  XY at = poly.back();
  for (size_t i = 1; i < poly.size(); ++i) {
    const double d = dist(poly[i - 1], poly[i]);
    if (d >= left) {
      const double s = left / d;
      at = {poly[i - 1].x + s * (poly[i].x - poly[i - 1].x),
            poly[i - 1].y + s * (poly[i].y - poly[i - 1].y)};
      break;
    }
    left -= d;
  }
  const double len = dist(poly.front(), at);
  return len > 0 ? XY{(at.x - poly.front().x) / len, (at.y - poly.front().y) / len} : XY{0, 0};
}

}  // namespace

std::vector<std::pair<XY, XY>> junction_tangents(
    std::span<const std::vector<XY>> polys, std::span<const std::pair<uint32_t, uint32_t>> ends,
    std::span<const double> weights) {
  constexpr double kAgreement = 0.5;  // |weighted mean| / total weight an axis needs
  struct Axis {
    double c = 0, s = 0, w = 0;  // sums of w cos 2a, w sin 2a, w
    int legs = 0;
  };
  std::unordered_map<uint32_t, Axis> axes;
  std::vector<std::pair<XY, XY>> legs(polys.size());  // leaving each end, into the bundle
  for (size_t b = 0; b < polys.size(); ++b) {
    std::vector<XY> reversed(polys[b].rbegin(), polys[b].rend());
    legs[b] = {leg_direction(polys[b]), leg_direction(reversed)};
    for (auto [node, leg] :
         {std::pair{ends[b].first, legs[b].first}, std::pair{ends[b].second, legs[b].second}}) {
      if (leg.x == 0 && leg.y == 0) continue;
      const double a = 2 * std::atan2(leg.y, leg.x);
      Axis& x = axes[node];
      x.c += weights[b] * std::cos(a), x.s += weights[b] * std::sin(a), x.w += weights[b];
      ++x.legs;
    }
  }
  // The axis at `node`, pointing along `leg` ({0, 0}: free).
  auto tangent = [&](uint32_t node, XY leg) {
    const Axis& x = axes[node];
    if (x.legs < 2 || !(std::hypot(x.c, x.s) >= kAgreement * x.w)) return XY{0, 0};
    const double a = std::atan2(x.s, x.c) / 2;
    XY t{std::cos(a), std::sin(a)};
    if (t.x * leg.x + t.y * leg.y < 0) t = {-t.x, -t.y};
    return t;
  };
  std::vector<std::pair<XY, XY>> out(polys.size());
  for (size_t b = 0; b < polys.size(); ++b) {
    const XY in = tangent(ends[b].second, legs[b].second);  // points back into the bundle
    out[b] = {tangent(ends[b].first, legs[b].first), {-in.x, -in.y}};
  }
  return out;
}

}  // namespace globe
