// Terrain tiles as TINs (see terrain_mesh.hpp).
#include "terrain_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

namespace globe::web {
namespace {

// Largest |height - plane| over the samples of triangle a b c (inclusive),
// the plane through the heights at its corners.
float triangle_error(const TileGrid& g, GridPoint a, GridPoint b, GridPoint c) {
  const double ha = g.at(a.i, a.j), hb = g.at(b.i, b.j), hc = g.at(c.i, c.j);
  const long area = long(b.i - a.i) * (c.j - a.j) - long(b.j - a.j) * (c.i - a.i);
  if (area == 0) return 0;
  const int i0 = std::min({a.i, b.i, c.i}), i1 = std::max({a.i, b.i, c.i});
  const int j0 = std::min({a.j, b.j, c.j}), j1 = std::max({a.j, b.j, c.j});
  double worst = 0;
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      // Barycentric weights times `area`; all of one sign inside.
      const long wa = long(b.i - i) * (c.j - j) - long(b.j - j) * (c.i - i);
      const long wb = long(c.i - i) * (a.j - j) - long(c.j - j) * (a.i - i);
      const long wc = area - wa - wb;
      if (area > 0 ? (wa < 0 || wb < 0 || wc < 0) : (wa > 0 || wb > 0 || wc > 0)) continue;
      const double plane = (wa * ha + wb * hb + wc * hc) / double(area);
      worst = std::max(worst, std::fabs(g.at(i, j) - plane));
    }
  return float(worst);
}

}  // namespace

std::vector<float> own_errors(const TileGrid& grid, double sample_metres) {
  const int n = grid.steps;
  std::vector<float> e(size_t(n + 1) * (n + 1), 0.0f);
  auto ref = [&](int i, int j) -> float& { return e[size_t(j) * (n + 1) + size_t(i)]; };
  constexpr double kEarthRadius = 6378137.0;
  for (int s = 2; s <= n; s *= 2) {
    const int h = s / 2;
    // Sagittas of the hypotenuses: s for an edge's triangles, s sqrt 2 for a square's.
    const double d = s * sample_metres;
    const float edge_sagitta = float(d * d / (8 * kEarthRadius));
    const float square_sagitta = 2 * edge_sagitta;
    // Midpoints of the edges of length s: each with the triangle(s) towards
    // the centres of scale s on either side that lie in the tile.
    for (int j0 = 0; j0 <= n; j0 += h)
      for (int i0 = 0; i0 <= n; i0 += h) {
        const bool horizontal = (j0 % s == 0) && (i0 % s == h);
        const bool vertical = (i0 % s == 0) && (j0 % s == h);
        if (!horizontal && !vertical) continue;
        float err = 0;
        for (int side : {-1, 1}) {
          const GridPoint c =
              horizontal ? GridPoint{i0, j0 + side * h} : GridPoint{i0 + side * h, j0};
          if (c.i < 0 || c.i > n || c.j < 0 || c.j > n) continue;
          const GridPoint p1 = horizontal ? GridPoint{i0 - h, j0} : GridPoint{i0, j0 - h};
          const GridPoint p2 = horizontal ? GridPoint{i0 + h, j0} : GridPoint{i0, j0 + h};
          err = std::max({err, edge_sagitta, triangle_error(grid, c, p1, p2)});
        }
        ref(i0, j0) = err;
      }
    // Centres of the squares of side s: the square's two halves.
    for (int j0 = 0; j0 < n; j0 += s)
      for (int i0 = 0; i0 < n; i0 += s) {
        const int orient = s == n ? grid.diagonal : ((i0 / s + j0 / s) & 1);
        const GridPoint tl{i0, j0}, tr{i0 + s, j0}, bl{i0, j0 + s}, br{i0 + s, j0 + s};
        ref(i0 + h, j0 + h) = orient == 0
                                  ? std::max({square_sagitta, triangle_error(grid, tr, tl, br),
                                              triangle_error(grid, bl, tl, br)})
                                  : std::max({square_sagitta, triangle_error(grid, tl, tr, bl),
                                              triangle_error(grid, br, tr, bl)});
      }
  }
  return e;
}

MeshErrors::MeshErrors(int steps, int diagonal, const std::array<const std::vector<float>*, 9>& own)
    : steps_(steps), diagonal_(diagonal) {
  // The 3 x 3 tiles' own errors on one grid; a shared edge's vertex takes
  // the larger of its two halves (the corners, never split vertices here, 0).
  const int n = steps, big = 3 * n;
  const size_t stride = size_t(big) + 1;
  std::vector<float> e(stride * stride, 0.0f);
  for (int t = 0; t < 9; ++t) {
    if (!own[t]) continue;
    const int ox = (t % 3) * n, oy = (t / 3) * n;
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        float& dst = e[size_t(oy + j) * stride + size_t(ox + i)];
        dst = std::max(dst, (*own[t])[size_t(j) * (n + 1) + size_t(i)]);
      }
  }
  // Saturation bottom up, scale s = 2 .. n: first the midpoints of the edges
  // of length s (children: the centres of scale s / 2 around them), then the
  // centres of the squares of side s (children: their edges' midpoints).
  auto at = [&](int i, int j) -> float& { return e[size_t(j) * stride + size_t(i)]; };
  for (int s = 2; s <= n; s *= 2) {
    const int h = s / 2, q = s / 4;
    if (q > 0)
      for (int j0 = 0; j0 <= big; j0 += h)
        for (int i0 = 0; i0 <= big; i0 += h) {
          const bool horizontal = (j0 % s == 0) && (i0 % s == h);
          const bool vertical = (i0 % s == 0) && (j0 % s == h);
          if (!horizontal && !vertical) continue;
          float& v = at(i0, j0);
          for (int a : {-q, q})
            for (int b : {-q, q}) {
              const int ci = i0 + a, cj = j0 + b;
              if (ci >= 0 && cj >= 0 && ci <= big && cj <= big) v = std::max(v, at(ci, cj));
            }
        }
    for (int j0 = 0; j0 < big; j0 += s)
      for (int i0 = 0; i0 < big; i0 += s) {
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
