// Area pipeline geometry (see area_geometry.hpp).
#include "areas/area_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace globe {

double ring_area2(const PlaneRing& r) {
  double a = 0;
  for (size_t i = 0, n = r.size(); i < n; ++i) {
    const PlanePoint& p = r[i];
    const PlanePoint& q = r[(i + 1) % n];
    a += p.x * q.y - q.x * p.y;
  }
  return a;
}

bool clean_ring(PlaneRing& r) {
  for (const PlanePoint& p : r)
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return false;
  r.erase(std::unique(r.begin(), r.end()), r.end());
  while (r.size() > 1 && r.front() == r.back())
    r.pop_back();
  return true;
}

namespace {

// Longitudes made continuous: each vertex moved by whole turns to within
// 180 degrees of the one before.
void unwrap(PlaneRing& r) {
  for (size_t i = 1; i < r.size(); ++i) {
    while (r[i].x - r[i - 1].x > 180)
      r[i].x -= 360;
    while (r[i].x - r[i - 1].x < -180)
      r[i].x += 360;
  }
}

std::pair<double, double> x_range(const PlaneRing& r) {
  double lo = 1e300, hi = -1e300;
  for (const PlanePoint& p : r)
    lo = std::min(lo, p.x), hi = std::max(hi, p.x);
  return {lo, hi};
}

void shift(PlanePolygon& p, double dx) {
  for (PlaneRing& r : p)
    for (PlanePoint& q : r)
      q.x += dx;
}

}  // namespace

PlaneMultiPolygon wrap_lonlat_polygon(const PlanePolygon& lonlat, Geos& geos, uint64_t& cuts) {
  PlanePolygon p = lonlat;
  for (PlaneRing& r : p)
    unwrap(r);
  PlaneRing& outer = p.front();
  // The closing edge, unwrapped: a ring whose longitudes add up to a whole
  // turn goes around a pole.
  double close = outer.front().x - outer.back().x;
  while (close > 180)
    close -= 360;
  while (close < -180)
    close += 360;
  const double turn = outer.back().x + close - outer.front().x;
  if (std::abs(turn) > 180) {
    double lat = 0;
    for (const PlanePoint& q : outer)
      lat += q.y;
    const double pole = lat >= 0 ? 90 : -90;
    const PlanePoint first = outer.front();
    outer.push_back({first.x + turn, first.y});
    outer.push_back({first.x + turn, pole});
    outer.push_back({first.x, pole});
  }
  // Holes next to their exterior.
  const auto [lo, hi] = x_range(outer);
  for (size_t i = 1; i < p.size(); ++i) {
    const auto [hlo, hhi] = x_range(p[i]);
    const double mid = (hlo + hhi) / 2;
    const double dx = mid < lo   ? 360 * std::ceil((lo - mid) / 360)
                      : mid > hi ? -360 * std::ceil((mid - hi) / 360)
                                 : 0;
    for (PlanePoint& q : p[i])
      q.x += dx;
  }
  if (lo >= -180 && hi <= 180) return {std::move(p)};
  ++cuts;
  // Whole turns that bring some of it into [-180, 180].
  PlaneMultiPolygon out;
  const int k0 = static_cast<int>(std::floor((lo + 180) / 360));
  const int k1 = static_cast<int>(std::floor((hi + 180) / 360));
  const PlaneMultiPolygon whole = geos.is_valid({p}) ? PlaneMultiPolygon{p} : geos.make_valid({p});
  for (int k = k0; k <= k1; ++k) {
    PlaneMultiPolygon moved = whole;
    for (PlanePolygon& q : moved)
      shift(q, -360.0 * k);
    for (PlanePolygon& q : geos.clip(moved, -180, -90, 180, 90))
      out.push_back(std::move(q));
  }
  return out;
}

void orient_for_tiles(PlaneMultiPolygon& m) {
  for (PlanePolygon& p : m)
    for (size_t i = 0; i < p.size(); ++i)
      if ((ring_area2(p[i]) > 0) != (i == 0)) std::reverse(p[i].begin(), p[i].end());
}

PlaneMultiPolygon to_zoom_grid(const PlaneMultiPolygon& frame, const tileformat::Tiling& t, int z,
                               int extent) {
  const double s = extent / t.tile_size(z);
  PlaneMultiPolygon out = frame;
  for (PlanePolygon& p : out)
    for (PlaneRing& r : p)
      for (PlanePoint& q : r)
        q = {(q.x - t.origin_x) * s, (t.origin_y - q.y) * s};
  return out;
}

namespace {

// Repeats and spikes (a-b-a) removed, until none is left.
void tidy(PlaneRing& r) {
  bool changed = true;
  while (changed && r.size() >= 3) {
    changed = false;
    r.erase(std::unique(r.begin(), r.end()), r.end());
    while (r.size() > 1 && r.front() == r.back())
      r.pop_back();
    for (size_t i = 0; r.size() >= 3 && i < r.size(); ++i) {
      const size_t prev = (i + r.size() - 1) % r.size(), next = (i + 1) % r.size();
      if (r[prev] == r[next]) {
        // a-b-a: b and one a go.
        const size_t lo = std::min(i, next), hi = std::max(i, next);
        r.erase(r.begin() + static_cast<long>(hi));
        r.erase(r.begin() + static_cast<long>(lo));
        changed = true;
        break;
      }
    }
  }
}

}  // namespace

PlaneMultiPolygon snap_polygons(const PlaneMultiPolygon& grid, double step, bool keep_collapsed,
                                uint64_t& dropped) {
  PlaneMultiPolygon out;
  for (const PlanePolygon& p : grid) {
    PlanePolygon q;
    for (const PlaneRing& r : p) {
      PlaneRing s;
      s.reserve(r.size());
      for (const PlanePoint& v : r)
        s.push_back({std::round(v.x / step) * step, std::round(v.y / step) * step});
      tidy(s);
      if (s.size() >= 3 && ring_area2(s) != 0) {
        q.push_back(std::move(s));
      } else if (q.empty()) {
        break;  // the exterior collapsed
      }
    }
    if (q.empty()) {
      if (!keep_collapsed || p.empty() || p.front().empty()) {
        ++dropped;
        continue;
      }
      const PlanePoint c{std::floor(p.front().front().x / step) * step,
                         std::floor(p.front().front().y / step) * step};
      q.push_back({c, {c.x + step, c.y}, {c.x + step, c.y + step}, {c.x, c.y + step}});
    }
    out.push_back(std::move(q));
  }
  orient_for_tiles(out);
  return out;
}

}  // namespace globe
