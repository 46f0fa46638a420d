// Package writer/reader: MBTiles schema, TMS rows, deduplication, atomic
// commit (temporary name, rollback), refusal to overwrite, resuming a
// killed writer.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include "test_support.hpp"
#include "tileformat/error.hpp"
#include "tileformat/package.hpp"

namespace tileformat {
// The package's own database, for tests that look under the API.
struct PackageTestAccess {
  static SqliteDb& db(PackageWriter& w) { return w.db(); }
  static SqliteDb& db(PackageReader& r) { return r.db(); }
};
}  // namespace tileformat

using globe_test::TempDir;
using tileformat::PackageReader;
using tileformat::PackageWriter;
using tileformat::TileId;

TEST(Package, WritesReadsAndDeduplicates) {
  TempDir dir;
  const auto path = (dir / "p.mbtiles").string();
  const std::vector<uint8_t> a{1, 2, 3}, b{4, 5};
  {
    PackageWriter w(path, tileformat::IfExists::kFail);
    w.put_tile({2, 1, 0}, a);
    w.put_tile({2, 2, 3}, a);
    w.put_tile({1, 1, 1}, b);
    w.set_metadata("name", "test");
    w.set_metadata("format", "application/vnd.globe.mblock");
    EXPECT_FALSE(std::filesystem::exists(path)) << "final name used before commit";
    w.commit();
  }
  PackageReader r(path);
  EXPECT_EQ(r.application_id(), tileformat::kApplicationId);
  EXPECT_EQ(*r.meta("name"), "test");
  EXPECT_EQ(*r.tile({2, 1, 0}), a);
  EXPECT_EQ(*r.tile({2, 2, 3}), a);
  EXPECT_EQ(*r.tile({1, 1, 1}), b);
  EXPECT_FALSE(r.tile({2, 0, 0}).has_value());
  EXPECT_EQ(r.unique_blobs(), 2u);
  // TMS storage: y = 0 at zoom 2 is row 3.
  EXPECT_EQ(tileformat::PackageTestAccess::db(r).query_int(
                "SELECT tile_row FROM tiles WHERE zoom_level = 2 AND tile_column = 1"),
            3);
}

// A reader starts memory-mapped (the viewer and the server read tiles again);
// stream() turns the map off for one-pass readers (the exports, analyze),
// whose mapped pages would otherwise stay resident, and reads the same tiles.
TEST(Package, StreamedReaderDropsTheMapAndReadsTheSameTiles) {
  TempDir dir;
  const auto path = (dir / "p.mbtiles").string();
  const std::vector<uint8_t> a(70000, 7);  // spans several database pages
  {
    PackageWriter w(path, tileformat::IfExists::kFail);
    w.put_tile({3, 1, 2}, a);
    w.set_metadata("format", "application/vnd.globe.mblock");
    w.commit();
  }
  PackageReader r(path);
  tileformat::SqliteDb& db = tileformat::PackageTestAccess::db(r);
  EXPECT_GT(db.query_int("PRAGMA mmap_size").value_or(0), 0);
  r.stream();
  EXPECT_EQ(db.query_int("PRAGMA mmap_size").value_or(-1), 0);
  EXPECT_EQ(*r.tile({3, 1, 2}), a);
}

TEST(Package, UncommittedWriterLeavesNothing) {
  TempDir dir;
  const auto path = (dir / "p.mbtiles").string();
  {
    PackageWriter w(path, tileformat::IfExists::kFail);
    w.put_tile({0, 0, 0}, std::vector<uint8_t>{1});
  }
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
}

TEST(Package, RefusesExistingOutputWithoutOverwrite) {
  TempDir dir;
  const auto path = (dir / "p.mbtiles").string();
  std::ofstream(path) << "precious";
  EXPECT_THROW(PackageWriter(path, tileformat::IfExists::kFail), tileformat::PackageError);
  EXPECT_EQ(globe_test::read_file(path), "precious");
}

TEST(Package, ReaderRejectsNonPackages) {
  TempDir dir;
  const auto path = (dir / "text.mbtiles").string();
  std::ofstream(path) << "not a database at all, just text\n";
  EXPECT_THROW(PackageReader r(path), tileformat::PackageError);
  EXPECT_THROW(PackageReader r((dir / "missing.mbtiles").string()), tileformat::PackageError);
}

namespace {

// Puts tiles 0..n-1 of zoom 10 (distinct blobs), as a build would.
void put_tiles(PackageWriter& w, uint32_t from, uint32_t n) {
  for (uint32_t i = from; i < n; ++i)
    w.put_tile({10, i, 7}, std::vector<uint8_t>{uint8_t(i), uint8_t(i >> 8), 42});
}

}  // namespace

TEST(Package, ResumeContinuesAKilledWriterToTheSameBytes) {
  TempDir dir;
  const auto ref = (dir / "ref.mbtiles").string(), out = (dir / "out.mbtiles").string();
  {
    PackageWriter w(ref, tileformat::IfExists::kFail, "key", tileformat::Resume::kStartAfresh);
    put_tiles(w, 0, 700);
    w.set_metadata("name", "p");
    w.commit();
  }
  // A child process puts 700 tiles and dies without unwinding: the first
  // batch of 512 is committed, the rest is in a hot journal.
  const pid_t pid = ::fork();
  if (pid == 0) {
    PackageWriter w(out, tileformat::IfExists::kFail, "key", tileformat::Resume::kStartAfresh);
    put_tiles(w, 0, 700);
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(std::filesystem::exists(out + ".tmp"));
  EXPECT_THROW(
      PackageWriter(out, tileformat::IfExists::kFail, "another key", tileformat::Resume::kContinue),
      tileformat::PackageError);
  {
    PackageWriter w(out, tileformat::IfExists::kFail, "key", tileformat::Resume::kContinue);
    ASSERT_TRUE(w.resumed());
    EXPECT_EQ(w.tiles_at_zoom(10), 512u);
    put_tiles(w, static_cast<uint32_t>(w.tiles_at_zoom(10)), 700);
    w.set_metadata("name", "p");
    w.commit();
  }
  // The resumed file is the uninterrupted one, byte for byte.
  EXPECT_EQ(globe_test::read_file(out), globe_test::read_file(ref));
  EXPECT_FALSE(std::filesystem::exists(out + ".tmp-journal"));
}

// Rows a builder writes right after a tile (a shard's parts) are committed
// with that tile, even when it fills its batch: --resume skips committed
// tiles, so a tile committed without its rows would lose them.
TEST(Package, RowsWrittenAfterATileAreCommittedWithIt) {
  TempDir dir;
  const auto out = (dir / "out.mbtiles").string();
  // A child process puts 600 tiles, each followed by a row of its own, and
  // dies without unwinding; the batch of the first 512 tiles is committed.
  const pid_t pid = ::fork();
  if (pid == 0) {
    PackageWriter w(out, tileformat::IfExists::kFail, "key", tileformat::Resume::kStartAfresh);
    tileformat::PackageTestAccess::db(w).exec("CREATE TABLE extra (tile INTEGER NOT NULL)");
    for (uint32_t i = 0; i < 600; ++i) {
      w.put_tile({10, i, 7}, std::vector<uint8_t>{uint8_t(i), uint8_t(i >> 8), 42});
      tileformat::PackageTestAccess::db(w).exec("INSERT INTO extra VALUES (" + std::to_string(i) +
                                                ")");
    }
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  PackageWriter w(out, tileformat::IfExists::kFail, "key", tileformat::Resume::kContinue);
  ASSERT_TRUE(w.resumed());
  EXPECT_EQ(w.tiles_at_zoom(10), 512u);
  EXPECT_EQ(tileformat::PackageTestAccess::db(w).query_int("SELECT COUNT(*) FROM extra"), 512);
}
