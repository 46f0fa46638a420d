// Tiling: tile ranges and the default view zoom shared by every package kind.
#include <gtest/gtest.h>

#include "tileformat/tiling.hpp"

using tileformat::Bounds;
using tileformat::Tiling;

TEST(Tiling, ViewZoomIsTheDeepestZoomWhoseTileHoldsTheData) {
  const Tiling g = Tiling::geodetic();  // tiles of 180 degrees at zoom 0
  // 10 x 4 degrees fits a 11.25-degree tile (zoom 4), not a 5.625 one.
  EXPECT_EQ(g.view_zoom({10, 40, 20, 44}, 0, 12), 4);
  // The whole globe stays at the coarsest zoom.
  EXPECT_EQ(g.view_zoom({-180, -90, 180, 90}, 0, 12), 0);
  // Clamped to the package's zoom range.
  EXPECT_EQ(g.view_zoom({10, 40, 20, 44}, 6, 12), 6);
  EXPECT_EQ(g.view_zoom({10, 40, 20, 44}, 0, 3), 3);
  // A point-sized extent goes to the finest zoom.
  EXPECT_EQ(g.view_zoom({10, 40, 10, 40}, 0, 9), 9);
}

TEST(Tiling, ViewZoomUsesTheWiderSideInTilingUnits) {
  const Tiling w = Tiling::webmercator();
  const double tile5 = w.tile_size(5);
  EXPECT_EQ(w.view_zoom({0, 0, tile5, tile5 / 8}, 0, 20), 5);
  EXPECT_EQ(w.view_zoom({0, 0, tile5 / 8, tile5 * 1.01}, 0, 20), 4);
  const Tiling l = Tiling::local("EPSG:32633", 500000, 5000000, 4096);
  EXPECT_EQ(l.view_zoom({500000, 4999000, 501000, 5000000}, 0, 10), 2);
}
