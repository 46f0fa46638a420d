// Tile ids: parent/children, TMS flip, diagonal orientation.
#include <gtest/gtest.h>

#include "tileformat/tile_id.hpp"

using tileformat::TileId;

TEST(TileId, ChildrenAndParentAreInverse) {
  const TileId t{5, 17, 9};
  for (const TileId& c : t.children()) {
    EXPECT_EQ(c.parent(), t);
    EXPECT_EQ(c.z, 6);
    EXPECT_EQ(t.children()[c.child_index()], c);
  }
}

TEST(TileId, TmsRowFlip) {
  EXPECT_EQ(TileId::flip_row(0, 8), 7u);
  EXPECT_EQ(TileId::flip_row(7, 8), 0u);
  EXPECT_EQ(TileId::flip_row(TileId::flip_row(3, 16), 16), 3u);
}

TEST(TileId, DiagonalAlternatesLikeACheckerboard) {
  EXPECT_EQ((TileId{3, 0, 0}.diagonal()), 0);
  EXPECT_EQ((TileId{3, 1, 0}.diagonal()), 1);
  EXPECT_EQ((TileId{3, 1, 1}.diagonal()), 0);
}
