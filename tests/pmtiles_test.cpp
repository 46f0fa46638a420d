// The PMTiles v3 writer (lib/tileformat/pmtiles.hpp) read back by the
// independent reader written from the specification (spec_readers/): header
// counts, directories (root only and with leaf directories), runs and
// deduplicated contents, every tile's bytes; Hilbert tile ids against the
// spec's values and the reader's conversion.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <optional>
#include <random>
#include <sstream>

#include "spec_readers/pmtiles_reader.hpp"
#include "test_support.hpp"
#include "tileformat/error.hpp"
#include "tileformat/pmtiles.hpp"
#include "tileformat/pmtiles_read.hpp"

namespace {

using namespace globe_test;
namespace pm = tileformat::pmtiles;
namespace ref = spec_readers::pmtiles;

std::vector<uint8_t> bytes_of(const std::string& s) {
  return std::vector<uint8_t>(s.begin(), s.end());
}

struct Tile {
  int z;
  uint32_t x, y;
  std::string bytes;
};

// Writes `tiles` (any order) and returns the archive's bytes.
std::string write_archive(const fs::path& path, std::vector<Tile> tiles,
                          const pm::ArchiveInfo& info = {}) {
  std::sort(tiles.begin(), tiles.end(), [](const Tile& a, const Tile& b) {
    return pm::tile_id(a.z, a.x, a.y) < pm::tile_id(b.z, b.x, b.y);
  });
  pm::PmtilesWriter w(path.string(), tileformat::IfExists::kOverwrite);
  for (const Tile& t : tiles)
    w.add(pm::tile_id(t.z, t.x, t.y), bytes_of(t.bytes));
  w.finish(info);
  EXPECT_EQ(w.bytes_written(), fs::file_size(path));
  return read_file(path);
}

}  // namespace

TEST(Pmtiles, TileIdsFollowTheSpecsHilbertCurve) {
  EXPECT_EQ(pm::tile_id(0, 0, 0), 0u);
  EXPECT_EQ(pm::tile_id(1, 0, 0), 1u);
  EXPECT_EQ(pm::tile_id(1, 0, 1), 2u);
  EXPECT_EQ(pm::tile_id(1, 1, 1), 3u);
  EXPECT_EQ(pm::tile_id(1, 1, 0), 4u);
  EXPECT_EQ(pm::tile_id(2, 0, 0), 5u);
  EXPECT_EQ(pm::tile_id(12, 3423, 1763), 19078479u);
  for (int z = 0; z <= 7; ++z)
    for (uint32_t x = 0; x < (1u << z); x += 3)
      for (uint32_t y = 0; y < (1u << z); y += 5) {
        const uint64_t id = pm::tile_id(z, x, y);
        ASSERT_EQ(id, ref::zxy_to_tile_id(z, x, y)) << z << "/" << x << "/" << y;
        ASSERT_EQ(pm::tile_zxy(id), (pm::Zxy{z, x, y}));
      }
  EXPECT_EQ(pm::tile_zxy(pm::tile_id(20, 1000000, 7)), (pm::Zxy{20, 1000000, 7}));
}

TEST(Pmtiles, ASmallArchiveReadsBackTileForTile) {
  TempDir dir;
  std::vector<Tile> tiles = {{0, 0, 0, "root"},   {1, 0, 0, "a"},     {1, 1, 0, "b"},
                             {1, 0, 1, "a"},      {1, 1, 1, "c"},     {2, 3, 3, "d"},
                             {3, 5, 2, "longer"}, {3, 6, 2, "longer"}};
  pm::ArchiveInfo info;
  info.tile_type = pm::TileType::kPng;
  info.min_zoom = 0, info.max_zoom = 3, info.center_zoom = 2;
  info.min_lon = -10.5, info.max_lon = 20.25, info.min_lat = -5, info.max_lat = 45.125;
  info.metadata_json = R"({"name":"test","format":"png"})";
  const std::string file = write_archive(dir / "small.pmtiles", tiles, info);
  const ref::Header h = ref::read_header(file);
  EXPECT_EQ(h.version, 3);
  EXPECT_TRUE(h.clustered);
  EXPECT_EQ(h.tile_type, ref::TileType::Png);
  EXPECT_EQ(h.leaf_dirs_length, 0u);
  EXPECT_EQ(h.min_zoom, 0);
  EXPECT_EQ(h.max_zoom, 3);
  EXPECT_EQ(h.min_lon_e7, -105000000);
  EXPECT_EQ(h.max_lat_e7, 451250000);
  EXPECT_EQ(h.addressed_tiles_count, 8u);
  EXPECT_EQ(h.tile_contents_count, 6u) << "a and longer stored once";
  EXPECT_EQ(ref::read_metadata(file), info.metadata_json);
  ref::validate_archive(file);
  for (const Tile& t : tiles)
    EXPECT_EQ(ref::get_tile(file, t.z, t.x, t.y).value_or("<none>"), t.bytes)
        << t.z << "/" << t.x << "/" << t.y;
  EXPECT_FALSE(ref::get_tile(file, 2, 0, 0).has_value());
}

// 40,000 tiles of zoom 8 (random bytes, some repeated, runs of equal
// neighbours): the root cannot hold them, so leaf directories; the header
// and the root still fit the first 16 KiB.
TEST(Pmtiles, ManyTilesGetLeafDirectories) {
  TempDir dir;
  std::mt19937 rng(5);
  std::vector<Tile> tiles;
  for (uint32_t x = 0; x < 256; ++x)
    for (uint32_t y = 0; y < 160; ++y) {
      const uint32_t r = rng() % 10;
      tiles.push_back({8, x, y, r < 3 ? "ocean" : "tile " + std::to_string(rng() % 20000)});
    }
  const std::string file = write_archive(dir / "many.pmtiles", tiles);
  const ref::Header h = ref::read_header(file);
  EXPECT_GT(h.leaf_dirs_length, 0u);
  EXPECT_LE(h.root_dir_offset + h.root_dir_length, 16384u);
  const auto entries = ref::validate_archive(file);
  EXPECT_LT(entries.size(), tiles.size()) << "runs of equal tiles";
  EXPECT_EQ(h.addressed_tiles_count, tiles.size());
  for (size_t i = 0; i < tiles.size(); i += 97)
    ASSERT_EQ(ref::get_tile(file, 8, tiles[i].x, tiles[i].y).value_or("<none>"), tiles[i].bytes);
}

TEST(Pmtiles, TilesOutOfOrderOrAnUnfinishedWriterLeaveNothing) {
  TempDir dir;
  const fs::path path = dir / "bad.pmtiles";
  {
    pm::PmtilesWriter w(path.string(), tileformat::IfExists::kFail);
    w.add(pm::tile_id(1, 0, 1), bytes_of("x"));
    EXPECT_THROW(w.add(pm::tile_id(1, 0, 0), bytes_of("y")), std::logic_error);
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_FALSE(fs::exists(path.string() + ".tmp"));
  EXPECT_FALSE(fs::exists(path.string() + ".tiles.tmp"));
  std::ofstream(path) << "there";
  EXPECT_THROW(pm::PmtilesWriter(path.string(), tileformat::IfExists::kFail),
               tileformat::PackageError);
  EXPECT_EQ(read_file(path), "there");
}

// The reading half (pmtiles_read.hpp, what globe-view's PMTiles source uses)
// finds every tile of an archive with leaf directories, following the
// header, root and leaves as a client does; absent tiles are absent.
TEST(PmtilesRead, FindsEveryTileThroughTheLeafDirectories) {
  TempDir dir;
  std::mt19937 rng(9);
  std::vector<Tile> tiles;
  for (uint32_t x = 0; x < 256; ++x)
    for (uint32_t y = 0; y < 160; ++y)
      tiles.push_back({8, x, y, rng() % 4 == 0 ? "sea" : "tile " + std::to_string(rng() % 9000)});
  const std::string file = write_archive(dir / "leaves.pmtiles", tiles);
  const auto bytes = [&](uint64_t at, uint64_t n) {
    return std::vector<uint8_t>(file.begin() + long(at), file.begin() + long(at + n));
  };
  const pm::Header h = pm::decode_header(bytes(0, pm::kHeaderSize));
  ASSERT_GT(h.leaf_length, 0u);
  EXPECT_EQ(h.info.min_zoom, 0);
  const std::vector<pm::Entry> root = pm::decode_directory(bytes(h.root_offset, h.root_length));
  const auto find = [&](int z, uint32_t x, uint32_t y) -> std::optional<std::string> {
    const uint64_t id = pm::tile_id(z, x, y);
    std::vector<pm::Entry> dir = root;
    for (int depth = 0; depth < 4; ++depth) {
      const pm::Entry* e = pm::find_entry(dir, id);
      if (!e) return std::nullopt;
      if (e->run_length > 0) {
        const auto b = bytes(h.data_offset + e->offset, e->length);
        return std::string(b.begin(), b.end());
      }
      dir = pm::decode_directory(bytes(h.leaf_offset + e->offset, e->length));
    }
    return std::nullopt;
  };
  for (size_t i = 0; i < tiles.size(); i += 37)
    ASSERT_EQ(find(8, tiles[i].x, tiles[i].y).value_or("<none>"), tiles[i].bytes) << i;
  EXPECT_FALSE(find(8, 0, 200));  // row 200 was never written
  EXPECT_FALSE(find(7, 0, 0));
}

TEST(PmtilesRead, MalformedBytesAreErrorsNotCrashes) {
  std::vector<uint8_t> h(pm::kHeaderSize, 0);
  EXPECT_THROW(pm::decode_header(std::span(h).first(100)), pm::PmtilesError);
  EXPECT_THROW(pm::decode_header(h), pm::PmtilesError);  // no magic
  std::memcpy(h.data(), "PMTiles\x02", 8);
  EXPECT_THROW(pm::decode_header(h), pm::PmtilesError);  // version 2
  // A directory that claims more entries than it has bytes, or ends mid-varint.
  EXPECT_THROW(pm::decode_directory(std::vector<uint8_t>{0xff, 0x7f}), pm::PmtilesError);
  EXPECT_THROW(pm::decode_directory(std::vector<uint8_t>{2, 1, 0x80}), pm::PmtilesError);
  // A first offset "right after the previous" has no previous.
  EXPECT_THROW(pm::decode_directory(std::vector<uint8_t>{1, 5, 1, 10, 0}), pm::PmtilesError);
  const std::vector<pm::Entry> ok = pm::decode_directory(std::vector<uint8_t>{1, 5, 2, 10, 1});
  ASSERT_EQ(ok.size(), 1u);
  EXPECT_EQ(ok[0].tile_id, 5u);
  EXPECT_EQ(pm::find_entry(ok, 6), &ok[0]);   // inside the run of 2
  EXPECT_EQ(pm::find_entry(ok, 7), nullptr);  // past it
  EXPECT_EQ(pm::find_entry(ok, 4), nullptr);  // before it
}
