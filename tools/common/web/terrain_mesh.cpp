// Terrain tiles as TINs (see terrain_mesh.hpp).
#include "web/terrain_mesh.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <mutex>

namespace globe::web {
namespace {

// The samples of a triangle of the hierarchy relative to its right-angle
// corner a, as runs along rows. Every triangle of one scale and orientation
// is a translate of the others, so these are made once per shape and grid
// width and kept for the process.
struct StencilRow {
  int32_t offset;  // of the run's first sample in TileGrid::h, from a's index
  int16_t di, dj;  // that sample's grid position, from a
  int32_t count;
};
// Small triangles (short rows) as single samples with their plane weights:
// plane = ha + wb (hb - ha) + wc (hc - ha), no loop per row.
struct StencilPoint {
  int32_t offset;
  double wb, wc;
};
struct Stencil {
  GridPoint db, dc;                  // b - a, c - a
  double inv_area = 0;               // 1 / ((b - a) x (c - a))
  bool corners_only = false;         // no sample but a, b and c: the plane holds them all
  std::vector<StencilRow> rows;      // for large triangles
  std::vector<StencilPoint> points;  // for small ones (rows empty)
};

// The samples (edges included) of triangle a, a + db, a + dc in a grid of
// rows `stride` samples apart.
Stencil make_stencil(int stride, GridPoint db, GridPoint dc) {
  const long area = long(db.i) * dc.j - long(db.j) * dc.i;
  Stencil out{db, dc, 1.0 / double(area), false, {}, {}};
  int samples = 0;
  const int i0 = std::min({0, db.i, dc.i}), i1 = std::max({0, db.i, dc.i});
  const int j0 = std::min({0, db.j, dc.j}), j1 = std::max({0, db.j, dc.j});
  for (int j = j0; j <= j1; ++j) {
    int first = INT32_MAX, last = INT32_MIN;
    for (int i = i0; i <= i1; ++i) {
      // Barycentric weights times `area`; all of one sign inside.
      const long wb = long(i) * dc.j - long(j) * dc.i;
      const long wc = long(db.i) * j - long(db.j) * i;
      const long wa = area - wb - wc;
      if (area > 0 ? (wa < 0 || wb < 0 || wc < 0) : (wa > 0 || wb > 0 || wc > 0)) continue;
      first = std::min(first, i), last = std::max(last, i);
      ++samples;
    }
    if (first <= last)  // a triangle's row inside it is one run
      out.rows.push_back(
          {int32_t(j * stride + first), int16_t(first), int16_t(j), last - first + 1});
  }
  out.corners_only = samples == 3;
  if (samples < 16 * int(out.rows.size())) {  // short rows: single samples are faster
    for (const StencilRow& r : out.rows)
      for (int k = 0; k < r.count; ++k) {
        const long i = r.di + k, j = r.dj;
        const double wb = double(i * dc.j - j * dc.i) * out.inv_area;
        const double wc = double(db.i * j - db.j * i) * out.inv_area;
        out.points.push_back({r.offset + k, wb, wc});
      }
    out.rows.clear();
  }
  return out;
}

// The eight triangle shapes of scale s (own_errors's loops): for edge
// midpoints, the triangles towards the centre on each side of a horizontal
// and of a vertical edge; for squares, the two halves in either orientation.
struct ScaleStencils {
  Stencil edge[2][2];    // [vertical][side > 0]
  Stencil square[2][2];  // [orientation][half]
};

const ScaleStencils& scale_stencils(int stride, int s) {
  static std::mutex mutex;
  static std::map<std::pair<int, int>, std::unique_ptr<ScaleStencils>> made;
  std::lock_guard lock(mutex);
  std::unique_ptr<ScaleStencils>& slot = made[{stride, s}];
  if (slot) return *slot;
  slot = std::make_unique<ScaleStencils>();
  const int h = s / 2;
  for (int vertical = 0; vertical < 2; ++vertical)
    for (int side = 0; side < 2; ++side) {
      const int d = side ? h : -h;
      // Right angle at the centre c; hypotenuse p1 (before) to p2 (after).
      const GridPoint p1 = vertical ? GridPoint{-d, -h} : GridPoint{-h, -d};
      const GridPoint p2 = vertical ? GridPoint{-d, h} : GridPoint{h, -d};
      slot->edge[vertical][side] = make_stencil(stride, p1, p2);
    }
  // Relative to the right-angle corner: orientation 0 halves (tr; tl, br)
  // and (bl; tl, br), orientation 1 (tl; tr, bl) and (br; tr, bl).
  slot->square[0][0] = make_stencil(stride, {-s, 0}, {0, s});
  slot->square[0][1] = make_stencil(stride, {0, -s}, {s, 0});
  slot->square[1][0] = make_stencil(stride, {s, 0}, {0, s});
  slot->square[1][1] = make_stencil(stride, {0, -s}, {-s, 0});
  return *slot;
}

// w as a float on the same side of `limit` as w: float(w) may round onto or
// across it. past: w > limit; within: w <= limit.
float past(double limit, double w) {
  float f = float(limit);
  if (double(f) <= limit) f = std::nextafter(f, INFINITY);
  return std::max(float(w), f);
}
float within(double limit, double w) {
  const float f = float(w);
  return double(f) > limit ? std::nextafter(f, -INFINITY) : f;
}

// Largest |height - plane| over the samples of triangle a b c (inclusive),
// the plane through the heights at its corners; `st` is its shape. Past
// `limit` the scan stops: the result is then only known to exceed it.
float triangle_error(const TileGrid& g, GridPoint a, GridPoint b, GridPoint c, const Stencil& st,
                     double limit) {
  if (st.corners_only) return 0;
  const double ha = g.at(a.i, a.j), db = g.at(b.i, b.j) - ha, dc = g.at(c.i, c.j) - ha;
  // The plane's gradient: (b - a) . grad = db, (c - a) . grad = dc.
  const double gi = (db * st.dc.j - dc * st.db.j) * st.inv_area;
  const double gj = (dc * st.db.i - db * st.dc.i) * st.inv_area;
  const double* at_a = &g.h[size_t(a.j + 1) * size_t(g.steps + 3) + size_t(a.i + 1)];
  double w0 = 0, w1 = 0;  // two chains: the loop is bound by max's latency
  size_t p = 0;
  for (; p + 1 < st.points.size(); p += 2) {
    const StencilPoint& u = st.points[p];
    const StencilPoint& v = st.points[p + 1];
    w0 = std::max(w0, std::fabs(at_a[u.offset] - (ha + u.wb * db + u.wc * dc)));
    w1 = std::max(w1, std::fabs(at_a[v.offset] - (ha + v.wb * db + v.wc * dc)));
    if (w0 > limit || w1 > limit) return past(limit, std::max(w0, w1));
  }
  if (p < st.points.size()) {
    const StencilPoint& u = st.points[p];
    w0 = std::max(w0, std::fabs(at_a[u.offset] - (ha + u.wb * db + u.wc * dc)));
  }
  for (const StencilRow& r : st.rows) {
    const double* h = at_a + r.offset;
    const double base = ha + r.di * gi + r.dj * gj;
    int k = 0;
    for (; k + 1 < r.count; k += 2) {
      w0 = std::max(w0, std::fabs(h[k] - (base + k * gi)));
      w1 = std::max(w1, std::fabs(h[k + 1] - (base + (k + 1) * gi)));
    }
    if (k < r.count) w0 = std::max(w0, std::fabs(h[k] - (base + k * gi)));
    if (w0 > limit || w1 > limit) return past(limit, std::max(w0, w1));
  }
  return float(std::max(w0, w1));
}

}  // namespace

std::vector<float> own_errors(const TileGrid& grid, double sample_metres, double limit) {
  const int n = grid.steps;
  std::vector<float> e(size_t(n + 1) * (n + 1), 0.0f);
  auto ref = [&](int i, int j) -> float& { return e[size_t(j) * (n + 1) + size_t(i)]; };
  constexpr double kEarthRadius = 6378137.0;
  const bool bounded = std::isfinite(limit);
  // Triangle a (right angle), b, c's error, or with a limit a cheaper answer
  // that decides a cut at it the same way. Its children (a; b, m) and
  // (a; m, c) split at the midpoints of its legs, whose errors are known
  // (finer first). Every sample lies in a child, whose plane departs from
  // this one by at most |h(m) - (h(b) + h(c)) / 2| (at m; 0 at the corners
  // they share): the children's errors plus that bound this one's. Within
  // the limit the bound stands in for the error; past it the scan decides;
  // and a child already past it splits this triangle's vertex anyway
  // (saturation), whatever its own error.
  auto error = [&](GridPoint a, GridPoint b, GridPoint c, const Stencil& st) -> float {
    if (!bounded) return triangle_error(grid, a, b, c, st, limit);
    float children = 0;
    if ((a.i + b.i) % 2 == 0 && (a.j + b.j) % 2 == 0)
      children =
          std::max(ref((a.i + b.i) / 2, (a.j + b.j) / 2), ref((a.i + c.i) / 2, (a.j + c.j) / 2));
    if (children > limit) return 0.0f;
    const double mid = grid.at((b.i + c.i) / 2, (b.j + c.j) / 2);
    const double bound = children + std::fabs(mid - (grid.at(b.i, b.j) + grid.at(c.i, c.j)) / 2);
    return bound <= limit ? within(limit, bound) : triangle_error(grid, a, b, c, st, limit);
  };
  for (int s = 2; s <= n; s *= 2) {
    const int h = s / 2;
    const ScaleStencils& st = scale_stencils(n + 3, s);
    // Sagittas of the hypotenuses: s for an edge's triangles, s sqrt 2 for a square's.
    const double d = s * sample_metres;
    const float edge_sagitta = float(d * d / (8 * kEarthRadius));
    const float square_sagitta = 2 * edge_sagitta;
    // Midpoints of the edges of length s: each with the triangle(s) towards
    // the centres of scale s on either side that lie in the tile.
    for (int j0 = 0; j0 <= n; j0 += h)
      for (int i0 = 0; i0 <= n; i0 += h) {
        const bool horizontal = (j0 & (s - 1)) == 0 && (i0 & (s - 1)) == h;  // s: a power of 2
        const bool vertical = (i0 & (s - 1)) == 0 && (j0 & (s - 1)) == h;
        if (!horizontal && !vertical) continue;
        float err = 0;
        if (edge_sagitta > limit) {  // split at any threshold up to the limit
          ref(i0, j0) = edge_sagitta;
          continue;
        }
        for (int side : {-1, 1}) {
          const GridPoint c =
              horizontal ? GridPoint{i0, j0 + side * h} : GridPoint{i0 + side * h, j0};
          if (c.i < 0 || c.i > n || c.j < 0 || c.j > n) continue;
          const GridPoint p1 = horizontal ? GridPoint{i0 - h, j0} : GridPoint{i0, j0 - h};
          const GridPoint p2 = horizontal ? GridPoint{i0 + h, j0} : GridPoint{i0, j0 + h};
          err = std::max({err, edge_sagitta, error(c, p1, p2, st.edge[vertical][side > 0])});
          if (err > limit) break;
        }
        ref(i0, j0) = err;
      }
    // Centres of the squares of side s: the square's two halves.
    for (int j0 = 0; j0 < n; j0 += s)
      for (int i0 = 0; i0 < n; i0 += s) {
        const int orient = s == n ? grid.diagonal : ((i0 / s + j0 / s) & 1);
        const GridPoint tl{i0, j0}, tr{i0 + s, j0}, bl{i0, j0 + s}, br{i0 + s, j0 + s};
        float& err = ref(i0 + h, j0 + h);
        err = square_sagitta;
        if (err > limit) continue;
        err = std::max(err, orient == 0 ? error(tr, tl, br, st.square[0][0])
                                        : error(tl, tr, bl, st.square[1][0]));
        if (err > limit) continue;
        err = std::max(err, orient == 0 ? error(bl, tl, br, st.square[0][1])
                                        : error(br, tr, bl, st.square[1][1]));
      }
  }
  return e;
}

MeshErrors::MeshErrors(int steps, int diagonal, const std::array<const std::vector<float>*, 9>& own)
    : steps_(steps), diagonal_(diagonal) {
  // The 3 x 3 tiles' own errors on one grid, global coordinates 0..3n with
  // the centre tile at n..2n; a shared edge's vertex takes the larger of its
  // two halves (the corners, never split vertices here, 0). A vertex's
  // descendants lie in its diamond, at most half its scale (n / 2 for the
  // centre tile's) away, so only the centre tile and a margin of n / 2
  // around it are kept: 4 n^2 values instead of 9 n^2.
  const int n = steps, lo = n / 2, hi = 2 * n + n / 2;
  const size_t stride = size_t(hi - lo) + 1;
  std::vector<float> e(stride * stride, 0.0f);
  auto at = [&](int i, int j) -> float& { return e[size_t(j - lo) * stride + size_t(i - lo)]; };
  for (int t = 0; t < 9; ++t) {
    if (!own[t]) continue;
    const int ox = (t % 3) * n, oy = (t / 3) * n;
    const int i0 = std::max(ox, lo), i1 = std::min(ox + n, hi);
    const int j0 = std::max(oy, lo), j1 = std::min(oy + n, hi);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        float& dst = at(i, j);
        dst = std::max(dst, (*own[t])[size_t(j - oy) * (n + 1) + size_t(i - ox)]);
      }
  }
  // Saturation bottom up, scale s = 2 .. n: first the midpoints of the edges
  // of length s (children: the centres of scale s / 2 around them), then the
  // centres of the squares of side s (children: their edges' midpoints).
  // lo is a multiple of s / 2, so the loops start on the global lattice;
  // children outside the kept region belong to no vertex that matters.
  for (int s = 2; s <= n; s *= 2) {
    const int h = s / 2, q = s / 4;
    if (q > 0)
      for (int j0 = lo; j0 <= hi; j0 += h)
        for (int i0 = lo; i0 <= hi; i0 += h) {
          const bool horizontal = (j0 & (s - 1)) == 0 && (i0 & (s - 1)) == h;
          const bool vertical = (i0 & (s - 1)) == 0 && (j0 & (s - 1)) == h;
          if (!horizontal && !vertical) continue;
          float& v = at(i0, j0);
          for (int a : {-q, q})
            for (int b : {-q, q}) {
              const int ci = i0 + a, cj = j0 + b;
              if (ci >= lo && cj >= lo && ci <= hi && cj <= hi) v = std::max(v, at(ci, cj));
            }
        }
    for (int j0 = (lo + s - 1) / s * s; j0 + s <= hi; j0 += s)
      for (int i0 = (lo + s - 1) / s * s; i0 + s <= hi; i0 += s) {
        float& v = at(i0 + h, j0 + h);
        v = std::max({v, at(i0 + h, j0), at(i0 + h, j0 + s), at(i0, j0 + h), at(i0 + s, j0 + h)});
      }
  }
  e_.resize(size_t(n + 1) * (n + 1));
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      e_[size_t(j) * (n + 1) + size_t(i)] = at(n + i, n + j);
}

std::vector<std::array<GridPoint, 3>> cut_mesh(const MeshErrors& errors, double threshold) {
  std::vector<std::array<GridPoint, 3>> out;
  // Triangle with its right angle at a, hypotenuse b-c.
  std::function<void(GridPoint, GridPoint, GridPoint)> visit = [&](GridPoint a, GridPoint b,
                                                                   GridPoint c) {
    const bool can_split = (b.i + c.i) % 2 == 0 && (b.j + c.j) % 2 == 0;
    const GridPoint m{(b.i + c.i) / 2, (b.j + c.j) / 2};
    if (can_split && errors.at(m.i, m.j) > threshold) {
      visit(m, b, a);
      visit(m, a, c);
      return;
    }
    // Counter-clockwise with i east and j south: negative area in (i, j).
    const long area = long(b.i - a.i) * (c.j - a.j) - long(b.j - a.j) * (c.i - a.i);
    if (area < 0)
      out.push_back({a, b, c});
    else
      out.push_back({a, c, b});
  };
  const int n = errors.steps();
  const GridPoint tl{0, 0}, tr{n, 0}, bl{0, n}, br{n, n};
  if (errors.diagonal() == 0) {
    visit(tr, tl, br);
    visit(bl, br, tl);
  } else {
    visit(tl, bl, tr);
    visit(br, tr, bl);
  }
  return out;
}

}  // namespace globe::web
