// Shard packages (tileformat/shard_table): the shard keys round-trip and are
// checked, the shard table stores parts by tag and tile (empty ones too) and
// survives a resumed writer without being created twice.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include "test_support.hpp"
#include "tileformat/error.hpp"
#include "tileformat/package.hpp"
#include "tileformat/shard_table.hpp"

using globe_test::TempDir;
using tileformat::TileId;

TEST(ShardMetadata, RoundTripsAndIsChecked) {
  tileformat::ShardMetadata m{2, 7, 5, 1234, "00ff00ff00ff00ff", 1, 3};
  const auto keys = tileformat::to_metadata(m);
  const auto back = tileformat::read_shard_metadata(keys);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->index, 2);
  EXPECT_EQ(back->count, 7);
  EXPECT_EQ(back->split_zoom, 5);
  EXPECT_EQ(back->roots, 1234u);
  EXPECT_EQ(back->build, m.build);
  EXPECT_EQ(back->min_zoom, 1);
  EXPECT_EQ(back->center_zoom, 3);
  EXPECT_FALSE(tileformat::read_shard_metadata({{"name", "x"}}));
  auto bad = keys;
  bad["globe:shard"] = "7/7";
  EXPECT_THROW(tileformat::read_shard_metadata(bad), tileformat::FormatError);
  bad = keys;
  bad.erase("globe:shard_build");
  EXPECT_THROW(tileformat::read_shard_metadata(bad), tileformat::FormatError);
  auto merged = keys;
  merged["name"] = "x";
  EXPECT_EQ(tileformat::without_shard_keys(merged), (tileformat::MetadataMap{{"name", "x"}}));
}

TEST(ShardTable, StoresPartsByTagAndTileAndSurvivesResume) {
  TempDir dir;
  const std::string path = (dir / "s.mbtiles").string();
  const std::vector<uint8_t> data{1, 2, 3};
  // A child process writes and dies without unwinding (a kill): the
  // temporary file keeps what was committed.
  const pid_t pid = ::fork();
  if (pid == 0) {
    tileformat::PackageWriter w(path, tileformat::IfExists::kFail, "key",
                                tileformat::Resume::kStartAfresh);
    tileformat::ShardTableWriter t(w);
    if (t.continued()) ::_exit(1);
    t.put(tileformat::kShardRoot, TileId{3, 5, 2}, {});
    t.put(tileformat::kShardRoot, TileId{3, 1, 4}, {});
    t.put(1, TileId{4, 10, 4}, data);
    w.put_tile(TileId{4, 10, 4}, data);
    w.checkpoint();
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  {
    tileformat::PackageWriter w(path, tileformat::IfExists::kFail, "key",
                                tileformat::Resume::kContinue);
    ASSERT_TRUE(w.resumed());
    {
      tileformat::ShardTableWriter t(w);
      EXPECT_TRUE(t.continued());
      t.put(2, TileId{4, 11, 4}, data);
    }  // its statement finalized before the writer closes the file
    w.put_tile(TileId{4, 11, 4}, data);
    w.commit();
  }
  tileformat::PackageReader r(path);
  tileformat::ShardTableReader t(r);
  EXPECT_EQ(t.list(tileformat::kShardRoot),
            (std::vector<TileId>{TileId{3, 5, 2}, TileId{3, 1, 4}}));
  ASSERT_TRUE(t.get(tileformat::kShardRoot, TileId{3, 5, 2}));
  EXPECT_TRUE(t.get(tileformat::kShardRoot, TileId{3, 5, 2})->empty());
  EXPECT_EQ(t.get(1, TileId{4, 10, 4}), data);
  EXPECT_EQ(t.get(2, TileId{4, 11, 4}), data);
  EXPECT_FALSE(t.get(1, TileId{4, 11, 4}));
}

TEST(ShardTable, APackageWithoutOneIsAFormatError) {
  TempDir dir;
  const std::string path = (dir / "p.mbtiles").string();
  {
    tileformat::PackageWriter w(path, tileformat::IfExists::kFail);
    w.put_tile(TileId{0, 0, 0}, std::vector<uint8_t>{1});
    w.commit();
  }
  tileformat::PackageReader r(path);
  EXPECT_THROW(tileformat::ShardTableReader{r}, tileformat::FormatError);
}
