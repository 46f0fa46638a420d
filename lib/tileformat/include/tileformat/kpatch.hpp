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

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace tileformat {

struct Point {
  int x = 0;
  int y = 0;
  bool operator==(const Point&) const = default;
};

// A level-m cell given relative to one block; cx, cy may leave the block by
// one block in any direction (-2^m .. 2^(m+1) - 1), where a neighbour's
// cells continue the grid.
struct Cell {
  int m = 0, cx = 0, cy = 0;
  bool operator==(const Cell&) const = default;
};

// A cell of the block at offset (dx, dy) (each -1, 0 or 1) from this one,
// in that block's own coordinates.
struct BlockCell {
  int dx = 0, dy = 0;
  Cell cell;
};
BlockCell locate_cell(const Cell& c);

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

  // The 4-8 hierarchy of split vertices (§6.1): a cell centre's children
  // are the midpoints of its four edges (top, bottom, left, right); an edge
  // midpoint's children are the centres of the four level-(m+1) cells that
  // touch it, two of which lie in the neighbour block across a block edge.
  std::array<size_t, 4> centre_children(int m, int cx, int cy) const {
    return {hedge_vertex(m, cy, cx), hedge_vertex(m, cy + 1, cx), vedge_vertex(m, cy, cx),
            vedge_vertex(m, cy, cx + 1)};
  }
  static std::array<Cell, 4> hedge_children(int m, int row, int cx) {
    return {Cell{m + 1, 2 * cx, 2 * row - 1}, Cell{m + 1, 2 * cx + 1, 2 * row - 1},
            Cell{m + 1, 2 * cx, 2 * row}, Cell{m + 1, 2 * cx + 1, 2 * row}};
  }
  static std::array<Cell, 4> vedge_children(int m, int cy, int col) {
    return {Cell{m + 1, 2 * col - 1, 2 * cy}, Cell{m + 1, 2 * col, 2 * cy},
            Cell{m + 1, 2 * col - 1, 2 * cy + 1}, Cell{m + 1, 2 * col, 2 * cy + 1}};
  }
  // The split vertex of depth `depth` at sample position `p` (the inverse of
  // vertex_position; p must be such a vertex).
  size_t vertex_at(int depth, Point p) const;
  // Across zooms: node `index` (depth >= 2) is the same triangle as a node two
  // depths shallower in one of the block's four child blocks (§6.1). Returns
  // the child (0..3 in TileId::children() order) and that node's index.
  std::pair<int, size_t> node_in_child(size_t index) const;

 private:
  int steps_, lattice_, depth_, diagonal_;
  std::vector<KPatchNode> nodes_;
  std::vector<size_t> node_offset_;    // depth -> first node; size D + 2
  std::vector<size_t> vertex_offset_;  // depth -> first vertex; size D + 2
  std::vector<Point> vertex_pos_;
};

// The 4-8 hierarchy over a whole tiling, in integer lattice units where a
// root tile is `root` units wide (root >> (level / 2) must stay even):
// the two parents of the split vertex `v` of level `level` (2 * zoom +
// depth in the block). Parents may lie outside the tiling.
struct LatticePoint {
  int64_t x = 0, y = 0;
  bool operator==(const LatticePoint&) const = default;
};
std::array<LatticePoint, 2> vertex_parents(LatticePoint v, int level, int64_t root);

// D for a block of `steps` steps and patch lattice L: 2 * log2(steps / L).
int kpatch_depth(int steps, int lattice);
// Number of split vertices of a tree of depth D (depths 0..D).
size_t kpatch_vertex_count(int depth);

}  // namespace tileformat
