// The viewer's image tile cache (viewer/data/image_cache): which requests
// are news to the imagery pass's settle loop. A request that is not news must
// not keep the loop drawing passes (tiles past the tiling's edge were asked
// for forever: five passes a frame).
#include <gtest/gtest.h>

#include "data/image_cache.hpp"
#include "runtime/image_package.hpp"
#include "test_support.hpp"

namespace {

using namespace globe_test;
using globe::viewer::ImageCache;
using tileformat::TileId;

TEST(ImageCache, OnlyNewTilesAreNews) {
  TempDir dir;
  const std::string path = (dir / "bm.mbtiles").string();
  ASSERT_EQ(
      run(tiler() + " imagery -q --max-zoom 1 " + sample("bluemarble.tif").string() + " -o " + path,
          dir.path())
          .exit_code,
      0);
  ImageCache cache(path, globe::open_image_package(path), 16);
  EXPECT_FALSE(cache.request(TileId{0, 1, 0})) << "east of +180 degrees at zoom 0";
  EXPECT_FALSE(cache.request(TileId{1, 0, 2})) << "south of the tiling at zoom 1";
  EXPECT_FALSE(cache.request(TileId{2, 0, 0})) << "finer than the package's maxzoom";
  EXPECT_TRUE(cache.request(TileId{0, 0, 0}));
  EXPECT_FALSE(cache.request(TileId{0, 0, 0})) << "already loading";
  cache.flush_requests();
  cache.wait_for_loader();
  EXPECT_EQ(cache.take_loaded().size(), 1u);
  EXPECT_FALSE(cache.request(TileId{0, 0, 0})) << "resident";
}

}  // namespace
