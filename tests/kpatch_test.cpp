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
