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

MeshErrors::MeshErrors(const TileGrid& grid, double sample_metres)
    : steps_(grid.steps),
      diagonal_(grid.diagonal),
      sample_metres_(sample_metres),
      grid_(&grid),
      e_(size_t(grid.steps + 1) * (grid.steps + 1), 0.0f) {
  saturate(true);
  grid_ = nullptr;  // the grid is needed only here
}

// Bottom up, scale s = 2, 4, ..., steps: first the midpoints of the edges of
// length s, then the centres of the squares of side s. `with_own` adds each
// vertex's own diamond triangles (first pass); without, only the children
// are taken again (after joining neighbours).
void MeshErrors::saturate(bool with_own) {
  const int n = steps_;
  constexpr double kEarthRadius = 6378137.0;
  for (int s = 2; s <= n; s *= 2) {
    const int h = s / 2, q = s / 4;
    // Sagittas of the hypotenuses: s for an edge's triangles, s sqrt 2 for a square's.
    const double d = s * sample_metres_;
    const float edge_sagitta = float(d * d / (8 * kEarthRadius));
    const float square_sagitta = 2 * edge_sagitta;
    // Edge midpoints: horizontal edges (mi, j0), vertical edges (i0, mj).
    for (int j0 = 0; j0 <= n; j0 += h)
      for (int i0 = 0; i0 <= n; i0 += h) {
        const bool horizontal = (j0 % s == 0) && (i0 % s == h);
        const bool vertical = (i0 % s == 0) && (j0 % s == h);
        if (!horizontal && !vertical) continue;
        float e = at(i0, j0);
        // The two centres of scale s on either side, each with its triangle.
        for (int side : {-1, 1}) {
          const GridPoint c =
              horizontal ? GridPoint{i0, j0 + side * h} : GridPoint{i0 + side * h, j0};
          if (c.i < 0 || c.i > n || c.j < 0 || c.j > n) continue;
          if (with_own) {
            const GridPoint p1 = horizontal ? GridPoint{i0 - h, j0} : GridPoint{i0, j0 - h};
            const GridPoint p2 = horizontal ? GridPoint{i0 + h, j0} : GridPoint{i0, j0 + h};
            e = std::max({e, edge_sagitta, triangle_error(*grid_, c, p1, p2)});
          }
          if (q > 0)  // children: centres of scale s / 2 on that side
            for (int t : {-1, 1}) {
              const GridPoint k = horizontal ? GridPoint{i0 + t * q, j0 + side * q}
                                             : GridPoint{i0 + side * q, j0 + t * q};
              e = std::max(e, at(k.i, k.j));
            }
        }
        ref(i0, j0) = e;
      }
    // Square centres.
    for (int j0 = 0; j0 < n; j0 += s)
      for (int i0 = 0; i0 < n; i0 += s) {
        const GridPoint c{i0 + h, j0 + h};
        float e = at(c.i, c.j);
        if (with_own) {
          e = std::max(e, square_sagitta);
          const int orient = s == n ? diagonal_ : ((i0 / s + j0 / s) & 1);
          const GridPoint tl{i0, j0}, tr{i0 + s, j0}, bl{i0, j0 + s}, br{i0 + s, j0 + s};
          if (orient == 0)
            e = std::max(
                {e, triangle_error(*grid_, tr, tl, br), triangle_error(*grid_, bl, tl, br)});
          else
            e = std::max(
                {e, triangle_error(*grid_, tl, tr, bl), triangle_error(*grid_, br, tr, bl)});
        }
        e = std::max({e, at(c.i, j0), at(c.i, j0 + s), at(i0, c.j), at(i0 + s, c.j)});
        ref(c.i, c.j) = e;
      }
  }
}

std::vector<float> MeshErrors::edge_halves(TileEdge edge) const {
  std::vector<float> out(size_t(steps_) + 1);
  for (int k = 0; k <= steps_; ++k) {
    switch (edge) {
      case TileEdge::kNorth:
        out[k] = at(k, 0);
        break;
      case TileEdge::kSouth:
        out[k] = at(k, steps_);
        break;
      case TileEdge::kWest:
        out[k] = at(0, k);
        break;
      case TileEdge::kEast:
        out[k] = at(steps_, k);
        break;
    }
  }
  return out;
}

void MeshErrors::join_neighbour(TileEdge edge, const std::vector<float>& halves) {
  for (int k = 0; k <= steps_ && size_t(k) < halves.size(); ++k) {
    float& e = edge == TileEdge::kNorth   ? ref(k, 0)
               : edge == TileEdge::kSouth ? ref(k, steps_)
               : edge == TileEdge::kWest  ? ref(0, k)
                                          : ref(steps_, k);
    e = std::max(e, halves[k]);
  }
}

void MeshErrors::finish() {
  saturate(false);
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
