// KPatch error trees (see error_tree.hpp).
#include "runtime/error_tree.hpp"

#include <algorithm>
#include <cmath>
#include <deque>

namespace globe {

using tileformat::Cell;
using tileformat::KPatchLayout;
using tileformat::KPatchNode;
using tileformat::Point;

namespace {

// The samples of one half-open lattice cell {apex + fa*wu + fb*wv, 0 <= fa,
// fb < 1} with their interpolation weights, split into the cell's lower
// triangle (fa + fb <= 1, from vertex 00) and upper one (from vertex 11); the
// same pattern repeats in every cell of every node with the same lattice step
// vectors. Weights are kept as integer numerators over ww = |wu|^2, so the
// deviation is exact: z * ww = corner * ww + a * (A - corner) + b * (B - corner).
struct LatticePattern {
  struct Sample {
    ptrdiff_t offset;
    int64_t a, b;  // lower: weights of 10 and 01 (from 00); upper: of 01 and 10 (from 11)
  };
  Point wu, wv;
  int size;
  int64_t ww = 1;
  std::vector<Sample> lower, upper;

  LatticePattern(Point u, Point v, int stride) : wu(u), wv(v), size(stride) {
    ww = int64_t{wu.x} * wu.x + int64_t{wu.y} * wu.y;
    const int reach = std::abs(wu.x) + std::abs(wu.y);
    for (int dy = -reach; dy <= reach; ++dy)
      for (int dx = -reach; dx <= reach; ++dx) {
        const int64_t a = int64_t{dx} * wu.x + int64_t{dy} * wu.y,
                      b = int64_t{dx} * wv.x + int64_t{dy} * wv.y;
        if (!(a >= 0 && a < ww && b >= 0 && b < ww) || (a == 0 && b == 0))
          continue;  // (0, 0) is a vertex
        const ptrdiff_t offset = static_cast<ptrdiff_t>(dy) * size + dx;
        if (a + b > ww)
          upper.push_back({offset, ww - a, ww - b});
        else
          lower.push_back({offset, a, b});
      }
  }
};

// Patterns by lattice step vectors and row stride (a handful per block
// shape), built once per thread. A deque: references stay valid as it grows.
const LatticePattern& pattern(Point wu, Point wv, int size) {
  thread_local std::deque<LatticePattern> cache;  // offsets depend on the row stride too
  for (const auto& p : cache)
    if (p.wu == wu && p.wv == wv && p.size == size) return p;
  cache.emplace_back(wu, wv, size);
  return cache.back();
}

// Max over the valid samples under node `n` of |lattice surface - sample|,
// times ww (integer), computed in T: int32_t where no term can overflow it
// (see lattice_deviation), which is about a sixth faster than int64_t.
template <typename T, bool kMasked>
T scaled_deviation(const KPatchNode& n, const LatticePattern& p, int L, int size, const int32_t* h,
                   const uint8_t* ok) {
  const ptrdiff_t du = static_cast<ptrdiff_t>(p.wu.y) * size + p.wu.x,
                  dv = static_cast<ptrdiff_t>(p.wv.y) * size + p.wv.x;
  const ptrdiff_t apex = static_cast<ptrdiff_t>(n.apex.y) * size + n.apex.x;
  const T ww = static_cast<T>(p.ww);
  T worst = 0;
  auto scan = [&](const std::vector<LatticePattern::Sample>& samples, ptrdiff_t base, T corner, T a,
                  T b) {
    const T c = corner * ww, da = a - corner, db = b - corner;
    for (const auto& s : samples) {
      const ptrdiff_t idx = base + s.offset;
      if (kMasked && !ok[idx]) continue;
      const T d = c + static_cast<T>(s.a) * da + static_cast<T>(s.b) * db - T{h[idx]} * ww;
      worst = std::max(worst, d < 0 ? static_cast<T>(-d) : d);
    }
  };
  for (int i = 0; i < L; ++i)
    for (int j = 0; i + j < L; ++j) {
      const ptrdiff_t base = apex + i * du + j * dv;
      const T h10 = h[base + du], h01 = h[base + dv];
      scan(p.lower, base, h[base], h10, h01);
      // Cells on the hypotenuse have only their lower half inside the node.
      if (i + j < L - 1) scan(p.upper, base, h[base + du + dv], h01, h10);
    }
  return worst;
}

template <typename T>
int64_t scaled_deviation(const KPatchNode& n, const LatticePattern& p, int L, int size,
                         const std::vector<int32_t>& q, const std::vector<uint8_t>& valid) {
  return valid.empty() ? scaled_deviation<T, false>(n, p, L, size, q.data(), nullptr)
                       : scaled_deviation<T, true>(n, p, L, size, q.data(), valid.data());
}

}  // namespace

double lattice_deviation(const KPatchLayout& layout, size_t index, const std::vector<int32_t>& q,
                         const std::vector<uint8_t>& valid, int64_t max_abs_q) {
  const KPatchNode& n = layout.nodes()[index];
  const int L = layout.lattice(), size = layout.steps() + 1;
  // Lattice step vectors along the two legs (integers for every depth <= D).
  const Point wu{(n.b.x - n.apex.x) / L, (n.b.y - n.apex.y) / L};
  const Point wv{(n.c.x - n.apex.x) / L, (n.c.y - n.apex.y) / L};
  const LatticePattern& p = pattern(wu, wv, size);
  // |corner * ww| + |s.a * da| + |s.b * db| + |h * ww| <= 6 * ww * max|q|, as
  // the weights s.a, s.b are at most ww and |da|, |db| <= 2 * max|q|: below
  // 2^31, int32_t holds every term and partial sum.
  const bool narrow = 6 * p.ww * max_abs_q < (int64_t{1} << 31);
  const int64_t d = narrow ? scaled_deviation<int32_t>(n, p, L, size, q, valid)
                           : scaled_deviation<int64_t>(n, p, L, size, q, valid);
  return static_cast<double>(d) / static_cast<double>(p.ww);
}

namespace {

uint32_t quanta(double v) {
  return static_cast<uint32_t>(std::ceil(v - 1e-9));
}

}  // namespace

std::vector<uint32_t> node_errors(const KPatchLayout& layout, const std::vector<int32_t>& q,
                                  const std::vector<uint8_t>& valid,
                                  const std::array<const std::vector<uint32_t>*, 4>& children) {
  const auto& nodes = layout.nodes();
  std::vector<uint32_t> err(nodes.size(), 0);
  const bool finest =
      std::none_of(children.begin(), children.end(), [](auto* c) { return c != nullptr; });
  int64_t max_abs_q = 0;
  for (int32_t v : q)
    max_abs_q = std::max(max_abs_q, std::abs(int64_t{v}));
  for (int d = layout.depth(); d >= 0; --d) {
    for (size_t i = layout.node_offset(d); i < layout.node_offset(d + 1); ++i) {
      const KPatchNode& n = nodes[i];
      const uint32_t below =
          n.children[0] < 0 ? 0 : std::max(err[n.children[0]], err[n.children[1]]);
      if (d >= 2 && !finest) {
        auto [c, ci] = layout.node_in_child(i);
        if (children[c]) {
          err[i] = (*children[c])[ci];
          continue;
        }
      }
      // Depth D draws every sample: no deviation from this block's own data.
      const uint32_t own =
          d == layout.depth() ? 0 : quanta(lattice_deviation(layout, i, q, valid, max_abs_q));
      // Finest data (or no finer data): exact, saturated. Coarser: a bound.
      err[i] = (finest || d >= 2) ? std::max(own, below) : own + below;
    }
  }
  return err;
}

std::vector<uint32_t> vertex_errors(const KPatchLayout& layout, const Neighbourhood& nb) {
  std::vector<uint32_t> out(layout.vertex_count(), 0);
  // Node errors of a cell given in coordinates that may leave the block by
  // one block in any direction (tileformat::locate_cell).
  auto errors_of = [&](const Cell& c, Cell& local) -> const std::vector<uint32_t>* {
    const tileformat::BlockCell bc = tileformat::locate_cell(c);
    local = bc.cell;
    return nb[bc.dy + 1][bc.dx + 1];
  };
  auto cell_error = [&](int m, int gx, int gy) -> uint32_t {
    Cell l;
    const auto* e = errors_of({m, gx, gy}, l);
    if (!e) return 0;
    return std::max((*e)[layout.even_node(m, l.cx, l.cy, 0)],
                    (*e)[layout.even_node(m, l.cx, l.cy, 1)]);
  };
  auto odd_error = [&](int m, int gx, int gy, int k) -> uint32_t {
    Cell l;
    const auto* e = errors_of({m, gx, gy}, l);
    return e ? (*e)[layout.odd_node(m, l.cx, l.cy, k)] : 0;
  };
  auto n3 = [&](int m, int gx, int gy) {
    uint32_t v = 0;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        v = std::max(v, cell_error(m, gx + dx, gy + dy));
    return v;
  };
  const int levels = layout.depth() / 2;
  for (int m = 0; m <= levels; ++m) {
    const int cells = 1 << m;
    for (int cy = 0; cy < cells; ++cy)
      for (int cx = 0; cx < cells; ++cx)
        out[layout.cell_vertex(m, cx, cy)] = n3(m, cx, cy);
    if (m == levels) break;
    // Horizontal edges: between cell (cx, row-1) above and (cx, row) below.
    for (int row = 0; row <= cells; ++row)
      for (int cx = 0; cx < cells; ++cx) {
        uint32_t v = std::max(odd_error(m, cx, row - 1, 2), odd_error(m, cx, row, 0));
        for (const Cell& c : KPatchLayout::hedge_children(m, row, cx))
          v = std::max(v, n3(c.m, c.cx, c.cy));
        out[layout.hedge_vertex(m, row, cx)] = v;
      }
    // Vertical edges: between cell (col-1, cy) on the left and (col, cy) on the right.
    for (int cy = 0; cy < cells; ++cy)
      for (int col = 0; col <= cells; ++col) {
        uint32_t v = std::max(odd_error(m, col - 1, cy, 1), odd_error(m, col, cy, 3));
        for (const Cell& c : KPatchLayout::vedge_children(m, cy, col))
          v = std::max(v, n3(c.m, c.cx, c.cy));
        out[layout.vedge_vertex(m, cy, col)] = v;
      }
  }
  return out;
}

}  // namespace globe
