// The KPatch bintree of one MBlock (docs/tileformat.md §6): a terrain-
// independent hierarchy of right triangles over the block's sample square,
// and the numbering of its nodes and split vertices. Pure geometry, shared by
// the tiler (error trees) and the viewer (patch selection).
//
// Coordinates are sample indices: x to the east (column), y to the south (row),
// 0..steps inclusive. Depth 2m nodes are the two halves of a level-m cell
// (a square of steps/2^m samples, split along its diagonal); depth 2m+1 nodes
// are the four triangles from a level-m cell's centre to one of its edges.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tileformat {

struct Point {
  int x = 0;
  int y = 0;
  bool operator==(const Point&) const = default;
};

// One bintree node: right angle at `apex`, legs apex->b and apex->c; the
// hypotenuse b-c is split at its midpoint (the node's split vertex).
struct KPatchNode {
  Point apex, b, c;
  int depth = 0;
  int32_t children[2] = {-1, -1};  // node indices, -1 for leaves
  int32_t vertex = -1;             // split-vertex index (-1 for leaves)
};

class KPatchLayout {
 public:
  // steps = samples per side - 1 (a power of two), lattice = triangle legs of
  // one drawn patch, in lattice steps (L). Requires steps >= 2 * lattice.
  // `diagonal` is TileId::diagonal() of the block: it only changes depth 0.
  KPatchLayout(int steps, int lattice, int diagonal);

  int steps() const { return steps_; }
  int lattice() const { return lattice_; }
  int depth() const { return depth_; }  // D: depth of the leaves
  const std::vector<KPatchNode>& nodes() const { return nodes_; }
  size_t node_offset(int depth) const { return node_offset_[depth]; }
  size_t vertex_count() const { return vertex_offset_.back(); }
  size_t vertex_offset(int depth) const { return vertex_offset_[depth]; }
  Point vertex_position(size_t index) const { return vertex_pos_[index]; }

  // Split vertices of depth 2m: centres of level-m cells.
  size_t cell_vertex(int m, int cx, int cy) const {
    return vertex_offset_[2 * m] + static_cast<size_t>(cy) * (size_t{1} << m) + cx;
  }
  // Split vertices of depth 2m+1: midpoints of the horizontal edge on top of
  // cell row `row` (0..2^m) or of the vertical edge left of cell column `col`.
  size_t hedge_vertex(int m, int row, int cx) const {
    return vertex_offset_[2 * m + 1] + static_cast<size_t>(row) * (size_t{1} << m) + cx;
  }
  size_t vedge_vertex(int m, int cy, int col) const {
    size_t n = size_t{1} << m;
    return vertex_offset_[2 * m + 1] + (n + 1) * n + static_cast<size_t>(cy) * (n + 1) + col;
  }
  // Even nodes (depth 2m): two per cell, t = 0/1. Odd nodes (depth 2m+1):
  // four per cell, k = 0 top, 1 right, 2 bottom, 3 left.
  size_t even_node(int m, int cx, int cy, int t) const {
    return node_offset_[2 * m] + (static_cast<size_t>(cy) * (size_t{1} << m) + cx) * 2 + t;
  }
  size_t odd_node(int m, int cx, int cy, int k) const {
    return node_offset_[2 * m + 1] + (static_cast<size_t>(cy) * (size_t{1} << m) + cx) * 4 + k;
  }
  // Diagonal orientation of a level-m cell of this block (0: TL-BR, 1: TR-BL).
  int cell_diagonal(int m, int cx, int cy) const {
    return m == 0 ? diagonal_ : static_cast<int>((cx + cy) & 1);
  }

 private:
  int steps_, lattice_, depth_, diagonal_;
  std::vector<KPatchNode> nodes_;
  std::vector<size_t> node_offset_;    // depth -> first node; size D + 2
  std::vector<size_t> vertex_offset_;  // depth -> first vertex; size D + 2
  std::vector<Point> vertex_pos_;
};

// D for a block of `steps` steps and patch lattice L: 2 * log2(steps / L).
int kpatch_depth(int steps, int lattice);
// Number of split vertices of a tree of depth D (depths 0..D).
size_t kpatch_vertex_count(int depth);

}  // namespace tileformat
