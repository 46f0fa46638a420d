// KPatch layout: node and vertex numbering, bisection geometry, and the
// global 4-8 hierarchy (a block's depth-d nodes are its children's depth d-2).
#include <gtest/gtest.h>

#include <set>

#include "tileformat/kpatch.hpp"
#include "tileformat/tile_id.hpp"

using tileformat::KPatchLayout;
using tileformat::Point;

TEST(KPatch, DepthAndCountsForTheDefaultBlock) {
  EXPECT_EQ(tileformat::kpatch_depth(256, 16), 8);
  const KPatchLayout l(256, 16, 0);
  EXPECT_EQ(l.nodes().size(), 1022u);
  EXPECT_EQ(l.vertex_count(), 541u);
  EXPECT_THROW(tileformat::kpatch_depth(16, 16), std::invalid_argument);
}

TEST(KPatch, ChildrenBisectTheHypotenuseAndVerticesAreMidpoints) {
  for (int diagonal : {0, 1}) {
    const KPatchLayout l(64, 16, diagonal);
    for (const auto& n : l.nodes()) {
      // Right angle at the apex, equal legs.
      const Point u{n.b.x - n.apex.x, n.b.y - n.apex.y}, v{n.c.x - n.apex.x, n.c.y - n.apex.y};
      EXPECT_EQ(u.x * v.x + u.y * v.y, 0);
      EXPECT_EQ(u.x * u.x + u.y * u.y, v.x * v.x + v.y * v.y);
      if (n.children[0] < 0) continue;
      const Point mid{(n.b.x + n.c.x) / 2, (n.b.y + n.c.y) / 2};
      EXPECT_EQ(l.vertex_position(n.vertex), mid);
      for (int32_t c : n.children) {
        EXPECT_EQ(l.nodes()[c].apex, mid);
        EXPECT_EQ(l.nodes()[c].depth, n.depth + 1);
      }
    }
  }
}

TEST(KPatch, EverySplitVertexIsSharedByAtMostTwoNodes) {
  const KPatchLayout l(256, 16, 1);
  std::vector<int> users(l.vertex_count(), 0);
  for (const auto& n : l.nodes())
    if (n.vertex >= 0) ++users[n.vertex];
  for (size_t v = 0; v < users.size(); ++v) {
    const Point p = l.vertex_position(v);
    const bool on_border = p.x == 0 || p.y == 0 || p.x == 256 || p.y == 256;
    // Depth-D vertices split leaves; that happens in the child blocks.
    const int expected = v >= l.vertex_offset(l.depth()) ? 0 : (on_border ? 1 : 2);
    EXPECT_EQ(users[v], expected) << "vertex " << v;
  }
}

TEST(KPatch, ChildBlockRootsAreDepthTwoNodesOfTheParent) {
  // Parent tile (3, 5, 2) and its children: depth-2 triangles of the parent,
  // scaled to child samples, must equal the children's root triangles.
  const tileformat::TileId parent{3, 5, 2};
  const KPatchLayout pl(64, 16, parent.diagonal());
  for (const auto& child : parent.children()) {
    const KPatchLayout cl(64, 16, child.diagonal());
    const int ox = (child.x & 1) * 32, oy = (child.y & 1) * 32;
    for (size_t r = 0; r < 2; ++r) {
      const auto& root = cl.nodes()[r];
      auto scaled = [&](Point p) { return Point{ox + p.x / 2, oy + p.y / 2}; };
      bool found = false;
      for (size_t i = pl.node_offset(2); i < pl.node_offset(3); ++i) {
        const auto& n = pl.nodes()[i];
        if (n.apex == scaled(root.apex) && ((n.b == scaled(root.b) && n.c == scaled(root.c)) ||
                                            (n.b == scaled(root.c) && n.c == scaled(root.b))))
          found = true;
      }
      EXPECT_TRUE(found) << "child " << child.str() << " root " << r;
    }
  }
}

TEST(KPatchHierarchy, VertexAtInvertsVertexPosition) {
  const KPatchLayout l(64, 4, 1);
  for (int d = 0; d < l.depth(); ++d)
    for (size_t v = l.vertex_offset(d); v < l.vertex_offset(d + 1); ++v)
      EXPECT_EQ(l.vertex_at(d, l.vertex_position(v)), v) << "depth " << d;
}

TEST(KPatchHierarchy, ChildrenAndParentsAreInverse) {
  // Within one block (root = steps), every child a vertex names lists that
  // vertex among its two parents, for either diagonal of the block.
  for (int diagonal : {0, 1}) {
    const KPatchLayout l(32, 4, diagonal);
    auto parents_of = [&](Point p, int level) {
      return tileformat::vertex_parents({p.x, p.y}, level, l.steps());
    };
    auto has_parent = [&](Point child, int level, Point parent) {
      for (const auto& q : parents_of(child, level))
        if (q.x == parent.x && q.y == parent.y) return true;
      return false;
    };
    // A block of diagonal 1 is the root cell of a tiling whose roots alternate.
    auto shifted = [&](Point p) { return Point{p.x + diagonal * l.steps(), p.y}; };
    for (int m = 0; 2 * m + 2 <= l.depth(); ++m) {
      const int cells = 1 << m;
      for (int cy = 0; cy < cells; ++cy)
        for (int cx = 0; cx < cells; ++cx) {
          const Point centre = l.vertex_position(l.cell_vertex(m, cx, cy));
          for (size_t c : l.centre_children(m, cx, cy))
            EXPECT_TRUE(has_parent(l.vertex_position(c), 2 * m + 1, centre));
        }
      for (int row = 0; row <= cells; ++row)
        for (int cx = 0; cx < cells; ++cx) {
          const Point edge = shifted(l.vertex_position(l.hedge_vertex(m, row, cx)));
          for (const tileformat::Cell& c : KPatchLayout::hedge_children(m, row, cx)) {
            const int s = l.steps() >> c.m;
            const Point centre = shifted({c.cx * s + s / 2, c.cy * s + s / 2});
            if (centre.y < 0) continue;  // above the tiling
            EXPECT_TRUE(has_parent(centre, 2 * m + 2, edge)) << "m " << m << " row " << row;
          }
        }
    }
  }
}

TEST(KPatchHierarchy, NodeInChildIsTheSameTriangle) {
  const tileformat::TileId parent{4, 6, 3};
  const KPatchLayout pl(64, 8, parent.diagonal());
  const auto children = parent.children();
  for (size_t i = pl.node_offset(2); i < pl.nodes().size(); ++i) {
    const auto [c, ci] = pl.node_in_child(i);
    const KPatchLayout cl(64, 8, children[c].diagonal());
    const int ox = (c & 1) * 32, oy = (c >> 1) * 32;
    auto up = [&](Point p) { return Point{ox + p.x / 2, oy + p.y / 2}; };
    const auto& n = pl.nodes()[i];
    const auto& m = cl.nodes()[ci];
    EXPECT_EQ(m.depth, n.depth - 2);
    EXPECT_EQ(up(m.apex), n.apex) << "node " << i;
    EXPECT_TRUE((up(m.b) == n.b && up(m.c) == n.c) || (up(m.b) == n.c && up(m.c) == n.b));
  }
}

TEST(KPatchHierarchy, LocateCellCrossesIntoNeighbours) {
  const auto w = tileformat::locate_cell({2, -1, 3});
  EXPECT_EQ(w.dx, -1);
  EXPECT_EQ(w.dy, 0);
  EXPECT_EQ(w.cell, (tileformat::Cell{2, 3, 3}));
  const auto se = tileformat::locate_cell({2, 4, 4});
  EXPECT_EQ(se.dx, 1);
  EXPECT_EQ(se.dy, 1);
  EXPECT_EQ(se.cell, (tileformat::Cell{2, 0, 0}));
}
