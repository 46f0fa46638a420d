// KPatch bintree layout (docs/tileformat.md §6).
#include "tileformat/kpatch.hpp"

#include <algorithm>
#include <bit>
#include <stdexcept>
#include <string>

namespace tileformat {

int kpatch_depth(int steps, int lattice) {
  if (steps <= 0 || !std::has_single_bit(static_cast<unsigned>(steps)) || lattice <= 0 ||
      !std::has_single_bit(static_cast<unsigned>(lattice)) || steps < 2 * lattice)
    throw std::invalid_argument("kpatch: steps (" + std::to_string(steps) + ") and lattice (" +
                                std::to_string(lattice) +
                                ") must be powers of two with steps >= 2 * lattice");
  return 2 * (std::countr_zero(static_cast<unsigned>(steps)) -
              std::countr_zero(static_cast<unsigned>(lattice)));
}

size_t kpatch_vertex_count(int depth) {
  size_t count = 0;
  for (int d = 0; d <= depth; ++d) {
    size_t n = size_t{1} << (d / 2);
    count += (d % 2 == 0) ? n * n : 2 * n * (n + 1);
  }
  return count;
}

KPatchLayout::KPatchLayout(int steps, int lattice, int diagonal)
    : steps_(steps), lattice_(lattice), depth_(kpatch_depth(steps, lattice)), diagonal_(diagonal) {
  node_offset_.push_back(0);
  vertex_offset_.push_back(0);
  for (int d = 0; d <= depth_; ++d) {
    size_t n = size_t{1} << (d / 2);
    node_offset_.push_back(node_offset_.back() + ((d % 2 == 0) ? 2 * n * n : 4 * n * n));
    vertex_offset_.push_back(vertex_offset_.back() + ((d % 2 == 0) ? n * n : 2 * n * (n + 1)));
  }
  nodes_.resize(node_offset_.back());
  vertex_pos_.resize(vertex_offset_.back());

  for (int d = 0; d <= depth_; ++d) {
    const int m = d / 2;
    const int cells = 1 << m;
    const int s = steps_ >> m;
    for (int cy = 0; cy < cells; ++cy) {
      for (int cx = 0; cx < cells; ++cx) {
        const Point tl{cx * s, cy * s}, tr{cx * s + s, cy * s}, bl{cx * s, cy * s + s},
            br{cx * s + s, cy * s + s}, centre{cx * s + s / 2, cy * s + s / 2};
        if (d % 2 == 0) {
          vertex_pos_[cell_vertex(m, cx, cy)] = centre;
          const bool tl_br = cell_diagonal(m, cx, cy) == 0;
          for (int t = 0; t < 2; ++t) {
            KPatchNode& node = nodes_[even_node(m, cx, cy, t)];
            if (tl_br)
              node = {t == 0 ? tr : bl, tl, br, d, {-1, -1}, -1};
            else
              node = {t == 0 ? tl : br, tr, bl, d, {-1, -1}, -1};
            if (d == depth_) continue;
            node.vertex = static_cast<int32_t>(cell_vertex(m, cx, cy));
            // Children: the two odd nodes whose edge touches the apex.
            const Point a = node.apex;
            int ks[2], n = 0;
            if (a.y == tl.y) ks[n++] = 0;  // top
            if (a.x == tr.x) ks[n++] = 1;  // right
            if (a.y == bl.y) ks[n++] = 2;  // bottom
            if (a.x == tl.x) ks[n++] = 3;  // left
            for (int i = 0; i < 2; ++i)
              node.children[i] = static_cast<int32_t>(odd_node(m, cx, cy, ks[i]));
          }
        } else {
          const Point ends[4][2] = {{tl, tr}, {tr, br}, {br, bl}, {bl, tl}};
          for (int k = 0; k < 4; ++k) {
            KPatchNode& node = nodes_[odd_node(m, cx, cy, k)];
            node = {centre, ends[k][0], ends[k][1], d, {-1, -1}, -1};
            node.vertex = static_cast<int32_t>(k == 0   ? hedge_vertex(m, cy, cx)
                                               : k == 2 ? hedge_vertex(m, cy + 1, cx)
                                               : k == 3 ? vedge_vertex(m, cy, cx)
                                                        : vedge_vertex(m, cy, cx + 1));
            vertex_pos_[node.vertex] = {(ends[k][0].x + ends[k][1].x) / 2,
                                        (ends[k][0].y + ends[k][1].y) / 2};
          }
        }
      }
    }
  }
  // Odd nodes' children: the halves of the two sub-cells along the edge whose
  // apex is the edge midpoint (filled after all even nodes exist).
  for (int d = 1; d < depth_; d += 2) {
    const int m = d / 2;
    for (size_t i = node_offset_[d]; i < node_offset_[d + 1]; ++i) {
      KPatchNode& node = nodes_[i];
      const Point mid{(node.b.x + node.c.x) / 2, (node.b.y + node.c.y) / 2};
      const int s = steps_ >> (m + 1);
      int n = 0;
      for (const Point& end : {node.b, node.c}) {
        // The sub-cell spanned by the centre/end diagonal contains both points.
        const int sx = std::min(node.apex.x, end.x) / s, sy = std::min(node.apex.y, end.y) / s;
        for (int t = 0; t < 2; ++t) {
          size_t child = even_node(m + 1, sx, sy, t);
          if (nodes_[child].apex == mid) node.children[n++] = static_cast<int32_t>(child);
        }
      }
      if (n != 2) throw std::logic_error("kpatch: inconsistent bintree layout");
    }
  }
}

BlockCell locate_cell(const Cell& c) {
  const int cells = 1 << c.m;
  const int dx = c.cx < 0 ? -1 : (c.cx >= cells ? 1 : 0);
  const int dy = c.cy < 0 ? -1 : (c.cy >= cells ? 1 : 0);
  return {dx, dy, Cell{c.m, c.cx - dx * cells, c.cy - dy * cells}};
}

size_t KPatchLayout::vertex_at(int depth, Point p) const {
  const int m = depth / 2, cs = steps_ >> m;
  if (depth % 2 == 0) return cell_vertex(m, (p.x - cs / 2) / cs, (p.y - cs / 2) / cs);
  if (p.x % cs == cs / 2) return hedge_vertex(m, p.y / cs, (p.x - cs / 2) / cs);
  return vedge_vertex(m, (p.y - cs / 2) / cs, p.x / cs);
}

std::pair<int, size_t> KPatchLayout::node_in_child(size_t index) const {
  const KPatchNode& n = nodes_[index];
  const int d = n.depth, m = d / 2;
  const size_t local = index - node_offset_[d];
  const size_t per_cell = (d % 2 == 0) ? 2 : 4;
  const int cells = 1 << m, cell = static_cast<int>(local / per_cell),
            sub = static_cast<int>(local % per_cell);
  const int cx = cell % cells, cy = cell / cells;
  const int half = cells / 2;  // level-m cells per child block side, at level m - 1 in the child
  const int qx = cx / half, qy = cy / half;
  const int lx = cx % half, ly = cy % half;
  const size_t child_index =
      (d % 2 == 0) ? even_node(m - 1, lx, ly, sub) : odd_node(m - 1, lx, ly, sub);
  return {qx + 2 * qy, child_index};
}

std::array<LatticePoint, 2> vertex_parents(LatticePoint v, int level, int64_t root) {
  const int64_t s = root >> (level >> 1), h = s / 2;
  if (level % 2 == 0) {  // centre of an s-square, split along its diagonal
    const int64_t i = (v.x - h) / s, j = (v.y - h) / s;
    if (((i + j) & 1) == 0)  // top-left to bottom-right: parents are TR and BL
      return {LatticePoint{v.x + h, v.y - h}, LatticePoint{v.x - h, v.y + h}};
    return {LatticePoint{v.x - h, v.y - h}, LatticePoint{v.x + h, v.y + h}};
  }
  if (v.x % s == h)  // midpoint of a horizontal edge: parents above and below
    return {LatticePoint{v.x, v.y - h}, LatticePoint{v.x, v.y + h}};
  return {LatticePoint{v.x - h, v.y}, LatticePoint{v.x + h, v.y}};
}

}  // namespace tileformat
