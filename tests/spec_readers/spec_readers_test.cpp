// Tests of the independent spec readers (PMTiles v3, quantized-mesh-1.0,
// RGB-encoded DEM pixels and the Web Mercator grid) on bytes built by hand in
// this file straight from the specifications, so that later tests can trust
// them when checking the project's own exporters.
#include <gtest/gtest.h>

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "spec_readers/pmtiles_reader.hpp"
#include "spec_readers/quantized_mesh_reader.hpp"
#include "spec_readers/raster_dem.hpp"

namespace {

namespace pm = spec_readers::pmtiles;
namespace qm = spec_readers::quantized_mesh;
namespace dem = spec_readers::raster_dem;

// ---------------------------------------------------------------------------
// Byte writers (little-endian), gzip, and an exception matcher.

void put_uint(std::string& out, std::uint64_t value, int width) {
  for (int i = 0; i < width; ++i)
    out.push_back(static_cast<char>((value >> (8 * i)) & 0xff));
}
void put_f32(std::string& out, float value) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, 4);
  put_uint(out, bits, 4);
}
void put_f64(std::string& out, double value) {
  std::uint64_t bits;
  std::memcpy(&bits, &value, 8);
  put_uint(out, bits, 8);
}
// Protobuf-style varint: 7 bits per byte, low group first.
void put_varint(std::string& out, std::uint64_t value) {
  while (value >= 0x80) {
    out.push_back(static_cast<char>((value & 0x7f) | 0x80));
    value >>= 7;
  }
  out.push_back(static_cast<char>(value));
}

std::string gzip(const std::string& in) {
  z_stream zs{};
  EXPECT_EQ(deflateInit2(&zs, 9, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY), Z_OK);
  std::string out(deflateBound(&zs, in.size()), '\0');
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data()));
  zs.avail_in = static_cast<uInt>(in.size());
  zs.next_out = reinterpret_cast<Bytef*>(&out[0]);
  zs.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&zs, Z_FINISH), Z_STREAM_END);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  return out;
}

// Expects `body` to throw std::runtime_error whose message contains `needle`.
void expect_error(const std::function<void()>& body, const std::string& needle) {
  try {
    body();
    ADD_FAILURE() << "expected an error containing \"" << needle << "\"";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos)
        << "message was: " << e.what() << "\nexpected to contain: " << needle;
  }
}

// ---------------------------------------------------------------------------
// A tiny PMTiles v3 writer following the spec: appendix A.1 for directories,
// section 3 for the header, sections laid out in the order of section 2.

std::string encode_directory(const std::vector<pm::Entry>& entries,
                             pm::Compression compression = pm::Compression::None) {
  std::string out;
  put_varint(out, entries.size());
  std::uint64_t last_id = 0;
  for (const pm::Entry& e : entries) {
    put_varint(out, e.tile_id - last_id);
    last_id = e.tile_id;
  }
  for (const pm::Entry& e : entries)
    put_varint(out, e.run_length);
  for (const pm::Entry& e : entries)
    put_varint(out, e.length);
  std::uint64_t next_byte = 0;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    put_varint(out, i > 0 && entries[i].offset == next_byte ? 0 : entries[i].offset + 1);
    next_byte = entries[i].offset + entries[i].length;
  }
  return compression == pm::Compression::Gzip ? gzip(out) : out;
}

std::string encode_header(const pm::Header& h) {
  std::string out = "PMTiles";
  out.push_back(static_cast<char>(h.version));
  for (std::uint64_t v :
       {h.root_dir_offset, h.root_dir_length, h.metadata_offset, h.metadata_length,
        h.leaf_dirs_offset, h.leaf_dirs_length, h.tile_data_offset, h.tile_data_length,
        h.addressed_tiles_count, h.tile_entries_count, h.tile_contents_count}) {
    put_uint(out, v, 8);
  }
  for (std::uint8_t b :
       {static_cast<std::uint8_t>(h.clustered), static_cast<std::uint8_t>(h.internal_compression),
        static_cast<std::uint8_t>(h.tile_compression), static_cast<std::uint8_t>(h.tile_type),
        h.min_zoom, h.max_zoom}) {
    out.push_back(static_cast<char>(b));
  }
  for (std::int32_t v : {h.min_lon_e7, h.min_lat_e7, h.max_lon_e7, h.max_lat_e7}) {
    put_uint(out, static_cast<std::uint32_t>(v), 4);
  }
  out.push_back(static_cast<char>(h.center_zoom));
  put_uint(out, static_cast<std::uint32_t>(h.center_lon_e7), 4);
  put_uint(out, static_cast<std::uint32_t>(h.center_lat_e7), 4);
  EXPECT_EQ(out.size(), 127u);
  return out;
}

// Lays out header, root directory, metadata, leaf directories, tile data and
// fills the section offsets / lengths of `h`.
std::string build_archive(pm::Header h, const std::string& root, const std::string& metadata,
                          const std::string& leaves, const std::string& tiles) {
  h.root_dir_offset = 127;
  h.root_dir_length = root.size();
  h.metadata_offset = h.root_dir_offset + root.size();
  h.metadata_length = metadata.size();
  h.leaf_dirs_offset = h.metadata_offset + metadata.size();
  h.leaf_dirs_length = leaves.size();
  h.tile_data_offset = h.leaf_dirs_offset + leaves.size();
  h.tile_data_length = tiles.size();
  return encode_header(h) + root + metadata + leaves + tiles;
}

pm::Header basic_header(pm::Compression internal = pm::Compression::None) {
  pm::Header h;
  h.version = 3;
  h.internal_compression = internal;
  h.tile_compression = pm::Compression::None;
  h.tile_type = pm::TileType::Png;
  return h;
}

std::string tile_content(std::uint64_t tile_id) {
  const pm::TileCoord c = pm::tile_id_to_zxy(tile_id);
  return "tile " + std::to_string(c.z) + "/" + std::to_string(c.x) + "/" + std::to_string(c.y);
}

// Appends one tile per id to `tiles` and returns the matching entries.
std::vector<pm::Entry> add_tiles(std::uint64_t first_id, std::uint64_t end_id, std::string& tiles) {
  std::vector<pm::Entry> entries;
  for (std::uint64_t id = first_id; id < end_id; ++id) {
    const std::string content = tile_content(id);
    entries.push_back({id, tiles.size(), static_cast<std::uint32_t>(content.size()), 1});
    tiles += content;
  }
  return entries;
}

// Patches byte `at` of `s`.
std::string with_byte(const std::string& s, std::size_t at, char value) {
  return s.substr(0, at) + value + s.substr(at + 1);
}
std::string with_u64(const std::string& s, std::size_t at, std::uint64_t value) {
  std::string le;
  put_uint(le, value, 8);
  return s.substr(0, at) + le + s.substr(at + 8);
}

// ---------------------------------------------------------------------------
// PMTiles: Hilbert tile ids (spec 4.1).

TEST(SpecReaders, HilbertTileIdsMatchSpecTable) {
  EXPECT_EQ(pm::zxy_to_tile_id(0, 0, 0), 0u);
  EXPECT_EQ(pm::zxy_to_tile_id(1, 0, 0), 1u);
  EXPECT_EQ(pm::zxy_to_tile_id(1, 0, 1), 2u);
  EXPECT_EQ(pm::zxy_to_tile_id(1, 1, 1), 3u);
  EXPECT_EQ(pm::zxy_to_tile_id(1, 1, 0), 4u);
  EXPECT_EQ(pm::zxy_to_tile_id(2, 0, 0), 5u);
  EXPECT_EQ(pm::zxy_to_tile_id(12, 3423, 1763), 19078479u);
  EXPECT_EQ(pm::tile_id_to_zxy(19078479), (pm::TileCoord{12, 3423, 1763}));
  EXPECT_EQ(pm::tile_id_to_zxy(4), (pm::TileCoord{1, 1, 0}));
  // Zoom bases (4^z - 1) / 3 and the last id of the deepest zoom.
  EXPECT_EQ(pm::first_tile_id_of_zoom(3), 21u);
  EXPECT_EQ(pm::zxy_to_tile_id(31, 0, 0), pm::first_tile_id_of_zoom(31));
  const std::uint32_t last = (1u << 31) - 1;
  const std::uint64_t max_id = pm::first_tile_id_of_zoom(32) - 1;
  EXPECT_EQ(pm::tile_id_to_zxy(max_id).z, 31);
  const pm::TileCoord c = pm::tile_id_to_zxy(max_id);
  EXPECT_EQ(pm::zxy_to_tile_id(31, c.x, c.y), max_id);
  // Like zoom 1 (id 4 = 1/1/0), each zoom's curve ends in the x = max, y = 0 corner.
  EXPECT_EQ(c, (pm::TileCoord{31, last, 0}));
  expect_error([] { pm::zxy_to_tile_id(2, 4, 0); }, "outside the 2^z x 2^z grid");
  expect_error([] { pm::zxy_to_tile_id(32, 0, 0); }, "zoom 32 is outside");
  expect_error([&] { pm::tile_id_to_zxy(max_id + 1); }, "beyond zoom 31");
}

TEST(SpecReaders, HilbertRoundTripZooms0To6) {
  for (int z = 0; z <= 6; ++z) {
    const std::uint32_t n = 1u << z;
    const std::uint64_t base = pm::first_tile_id_of_zoom(z);
    std::set<std::uint64_t> ids;
    for (std::uint32_t x = 0; x < n; ++x) {
      for (std::uint32_t y = 0; y < n; ++y) {
        const std::uint64_t id = pm::zxy_to_tile_id(z, x, y);
        ASSERT_GE(id, base);
        ASSERT_LT(id, base + std::uint64_t{n} * n);
        ASSERT_EQ(pm::tile_id_to_zxy(id), (pm::TileCoord{static_cast<std::uint8_t>(z), x, y}));
        ids.insert(id);
      }
    }
    EXPECT_EQ(ids.size(), std::size_t{n} * n) << "zoom " << z;
    // A Hilbert curve: consecutive ids are edge-adjacent tiles.
    for (std::uint64_t id = base + 1; id < base + std::uint64_t{n} * n; ++id) {
      const pm::TileCoord a = pm::tile_id_to_zxy(id - 1), b = pm::tile_id_to_zxy(id);
      const long step = std::labs(long(a.x) - long(b.x)) + std::labs(long(a.y) - long(b.y));
      ASSERT_EQ(step, 1) << "ids " << id - 1 << " and " << id;
    }
  }
}

// ---------------------------------------------------------------------------
// PMTiles: header and directories.

TEST(SpecReaders, PmtilesHeaderFieldsAreAllRead) {
  pm::Header h = basic_header(pm::Compression::Gzip);
  h.addressed_tiles_count = 1;
  h.tile_entries_count = 1;
  h.tile_contents_count = 1;
  h.clustered = true;
  h.tile_compression = pm::Compression::Zstd;
  h.tile_type = pm::TileType::Webp;
  h.min_zoom = 2;
  h.max_zoom = 14;
  h.min_lon_e7 = -1234567890;
  h.min_lat_e7 = -850511287;
  h.max_lon_e7 = 1800000000;
  h.max_lat_e7 = 850511287;
  h.center_zoom = 7;
  h.center_lon_e7 = -12345;
  h.center_lat_e7 = 456789;
  const std::string tiles = "x";
  const std::string file = build_archive(h, encode_directory({{0, 0, 1, 1}}, pm::Compression::Gzip),
                                         gzip("{\"name\":\"t\"}"), "", tiles);
  const pm::Header r = pm::read_header(file);
  EXPECT_EQ(r.version, 3);
  EXPECT_EQ(r.root_dir_offset, 127u);
  EXPECT_EQ(r.metadata_offset, r.root_dir_offset + r.root_dir_length);
  EXPECT_EQ(r.leaf_dirs_length, 0u);
  EXPECT_EQ(r.tile_data_offset, file.size() - 1);
  EXPECT_EQ(r.tile_data_length, 1u);
  EXPECT_EQ(r.addressed_tiles_count, 1u);
  EXPECT_EQ(r.tile_entries_count, 1u);
  EXPECT_EQ(r.tile_contents_count, 1u);
  EXPECT_TRUE(r.clustered);
  EXPECT_EQ(r.internal_compression, pm::Compression::Gzip);
  EXPECT_EQ(r.tile_compression, pm::Compression::Zstd);
  EXPECT_EQ(r.tile_type, pm::TileType::Webp);
  EXPECT_EQ(r.min_zoom, 2);
  EXPECT_EQ(r.max_zoom, 14);
  EXPECT_DOUBLE_EQ(r.min_lon(), -123.456789);
  EXPECT_DOUBLE_EQ(r.min_lat(), -85.0511287);
  EXPECT_DOUBLE_EQ(r.max_lon(), 180.0);
  EXPECT_DOUBLE_EQ(r.max_lat(), 85.0511287);
  EXPECT_EQ(r.center_zoom, 7);
  EXPECT_DOUBLE_EQ(r.center_lon(), -0.0012345);
  EXPECT_DOUBLE_EQ(r.center_lat(), 0.0456789);
  EXPECT_EQ(pm::read_metadata(file), "{\"name\":\"t\"}");
  EXPECT_EQ(pm::get_tile(file, 0, 0, 0), std::optional<std::string>("x"));
}

TEST(SpecReaders, PmtilesDirectoryDecodingFollowsSection4) {
  // Hand-encoded from spec 4.2: TileIDs 5, 42, 69 -> deltas 5, 37, 27; run
  // lengths 1, 3, 1; lengths 10, 300 (varint ac 02), 5; offsets 0 -> 0+1,
  // 10 = previous end -> 0, 0 (a repeated blob) -> 0+1.
  const std::string bytes(
      "\x03"
      "\x05\x25\x1b"
      "\x01\x03\x01"
      "\x0a\xac\x02\x05"
      "\x01\x00\x01",
      14);
  const std::vector<pm::Entry> entries = pm::decode_directory(bytes, pm::Compression::None);
  ASSERT_EQ(entries.size(), 3u);
  EXPECT_EQ(entries[0], (pm::Entry{5, 0, 10, 1}));
  EXPECT_EQ(entries[1], (pm::Entry{42, 10, 300, 3}));
  EXPECT_EQ(entries[2], (pm::Entry{69, 0, 5, 1}));
  // The same bytes gzip-compressed decode the same way.
  EXPECT_EQ(pm::decode_directory(gzip(bytes), pm::Compression::Gzip), entries);
  // And the test writer (appendix A.1) produces exactly these bytes.
  EXPECT_EQ(encode_directory(entries), bytes);
}

TEST(SpecReaders, PmtilesRootOnlyArchiveServesTiles) {
  std::string tiles;
  // Zooms 0..2: ids 0..20, one blob each, in id order (clustered).
  const std::vector<pm::Entry> entries = add_tiles(0, 21, tiles);
  pm::Header h = basic_header();
  h.clustered = true;
  h.addressed_tiles_count = 21;
  h.tile_entries_count = 21;
  h.tile_contents_count = 21;
  h.max_zoom = 2;
  const std::string file = build_archive(h, encode_directory(entries), "{}", "", tiles);
  EXPECT_EQ(pm::read_root_directory(file), entries);
  EXPECT_EQ(pm::read_all_entries(file), entries);
  EXPECT_EQ(pm::validate_archive(file), entries);
  for (int z = 0; z <= 2; ++z) {
    for (std::uint32_t x = 0; x < (1u << z); ++x) {
      for (std::uint32_t y = 0; y < (1u << z); ++y) {
        const auto tile = pm::get_tile(file, z, x, y);
        ASSERT_TRUE(tile.has_value());
        EXPECT_EQ(*tile,
                  "tile " + std::to_string(z) + "/" + std::to_string(x) + "/" + std::to_string(y));
      }
    }
  }
  EXPECT_FALSE(pm::get_tile(file, 3, 0, 0).has_value());
}

TEST(SpecReaders, PmtilesRunLengthEntriesCoverConsecutiveIds) {
  // Ids 1..4 (all of zoom 1) share one blob (run length 4); id 0 has its own;
  // id 6 repeats the zoom-0 blob (deduplicated, a lesser offset); id 5 absent.
  const std::string tiles = "ocean" + std::string("root");
  const std::vector<pm::Entry> entries = {{0, 5, 4, 1}, {1, 0, 5, 4}, {6, 5, 4, 1}};
  pm::Header h = basic_header();
  h.addressed_tiles_count = 6;
  h.tile_entries_count = 3;
  h.tile_contents_count = 2;
  const std::string file = build_archive(h, encode_directory(entries), "{}", "", tiles);
  EXPECT_EQ(pm::validate_archive(file), entries);
  EXPECT_EQ(pm::get_tile(file, 0, 0, 0), std::optional<std::string>("root"));
  for (std::uint32_t x = 0; x < 2; ++x) {
    for (std::uint32_t y = 0; y < 2; ++y) {
      EXPECT_EQ(pm::get_tile(file, 1, x, y), std::optional<std::string>("ocean"));
    }
  }
  EXPECT_EQ(pm::get_tile(file, 2, 0, 0), std::nullopt);  // id 5
  const pm::TileCoord six = pm::tile_id_to_zxy(6);
  EXPECT_EQ(pm::get_tile(file, six.z, six.x, six.y), std::optional<std::string>("root"));
  const pm::TileCoord seven = pm::tile_id_to_zxy(7);
  EXPECT_EQ(pm::get_tile(file, seven.z, seven.x, seven.y), std::nullopt);

  // Runs must not overlap: a run of 6 from id 1 would cover id 6 too.
  const std::string overlapping =
      build_archive(basic_header(), encode_directory({{0, 5, 4, 1}, {1, 0, 5, 6}, {6, 5, 4, 1}}),
                    "{}", "", tiles);
  expect_error([&] { pm::read_all_entries(overlapping); }, "overlaps tile id 6");
}

TEST(SpecReaders, PmtilesLeafDirectoriesWithGzipInternalCompression) {
  // Zooms 0..3 (ids 0..84) split over two leaf directories, everything
  // gzip-compressed individually (spec 4.2 "Compression").
  std::string tiles;
  const std::vector<pm::Entry> first = add_tiles(0, 30, tiles);
  std::vector<pm::Entry> second = add_tiles(30, 80, tiles);
  // Ids 80..84 as one run pointing at the blob of id 79.
  second.push_back({80, second.back().offset, second.back().length, 5});
  const std::string leaf_a = encode_directory(first, pm::Compression::Gzip);
  const std::string leaf_b = encode_directory(second, pm::Compression::Gzip);
  const std::vector<pm::Entry> root = {
      {0, 0, static_cast<std::uint32_t>(leaf_a.size()), 0},
      {30, leaf_a.size(), static_cast<std::uint32_t>(leaf_b.size()), 0}};
  pm::Header h = basic_header(pm::Compression::Gzip);
  h.clustered = true;
  h.addressed_tiles_count = 85;
  h.tile_entries_count = 81;
  h.tile_contents_count = 80;
  h.max_zoom = 3;
  const std::string file = build_archive(h, encode_directory(root, pm::Compression::Gzip),
                                         gzip("{\"type\":\"baselayer\"}"), leaf_a + leaf_b, tiles);
  EXPECT_EQ(pm::read_root_directory(file), root);
  std::vector<pm::Entry> all = first;
  all.insert(all.end(), second.begin(), second.end());
  EXPECT_EQ(pm::read_all_entries(file), all);
  EXPECT_EQ(pm::validate_archive(file), all);
  EXPECT_EQ(pm::read_metadata(file), "{\"type\":\"baselayer\"}");
  for (std::uint64_t id = 0; id < 85; ++id) {
    const pm::TileCoord c = pm::tile_id_to_zxy(id);
    EXPECT_EQ(pm::get_tile(file, c.z, c.x, c.y),
              std::optional<std::string>(tile_content(std::min<std::uint64_t>(id, 79))))
        << "tile id " << id;
  }
  EXPECT_FALSE(pm::get_tile(file, 4, 0, 0).has_value());

  // A leaf whose first entry does not carry the leaf entry's tile id.
  const std::vector<pm::Entry> bad_root = {
      {0, 0, static_cast<std::uint32_t>(leaf_a.size()), 0},
      {29, leaf_a.size(), static_cast<std::uint32_t>(leaf_b.size()), 0}};
  const std::string mislabelled = build_archive(basic_header(pm::Compression::Gzip),
                                                encode_directory(bad_root, pm::Compression::Gzip),
                                                gzip("{}"), leaf_a + leaf_b, tiles);
  expect_error([&] { pm::read_all_entries(mislabelled); },
               "first entry has tile id 30, expected the leaf entry's tile id 29");

  // A second leaf that starts inside the first one's range (ids 20..25 again)
  // gives non-increasing ids once expanded.
  const std::string leaf_c = encode_directory(
      std::vector<pm::Entry>(first.begin() + 20, first.begin() + 26), pm::Compression::Gzip);
  const std::vector<pm::Entry> overlapping_root = {
      {0, 0, static_cast<std::uint32_t>(leaf_a.size()), 0},
      {20, leaf_a.size(), static_cast<std::uint32_t>(leaf_c.size()), 0}};
  const std::string overlapping =
      build_archive(basic_header(pm::Compression::Gzip),
                    encode_directory(overlapping_root, pm::Compression::Gzip), gzip("{}"),
                    leaf_a + leaf_c, tiles);
  expect_error([&] { pm::read_all_entries(overlapping); },
               "non-increasing tile ids after expanding leaf directories: tile id 20 follows 29");

  // A leaf entry pointing past the leaf directories section.
  const std::vector<pm::Entry> long_root = {
      {0, 0, static_cast<std::uint32_t>(leaf_a.size() + leaf_b.size() + 1), 0}};
  const std::string past_end = build_archive(basic_header(pm::Compression::Gzip),
                                             encode_directory(long_root, pm::Compression::Gzip),
                                             gzip("{}"), leaf_a + leaf_b, tiles);
  expect_error([&] { pm::read_all_entries(past_end); },
               "out of bounds of the " + std::to_string(leaf_a.size() + leaf_b.size()) +
                   "-byte leaf directories section");
  expect_error([&] { pm::get_tile(past_end, 0, 0, 0); }, "leaf directories section");
}

// ---------------------------------------------------------------------------
// PMTiles: bad input.

TEST(SpecReaders, PmtilesBadMagicAndVersionThrow) {
  std::string tiles;
  const std::string good =
      build_archive(basic_header(), encode_directory(add_tiles(0, 1, tiles)), "{}", "", tiles);
  ASSERT_NO_THROW(pm::validate_archive(good));
  expect_error([&] { pm::read_header(with_byte(good, 0, 'X')); }, "bad magic at byte 0");
  expect_error([&] { pm::read_header(with_byte(good, 7, 2)); },
               "unsupported spec version 2 at byte 7");
  expect_error([&] { pm::read_header(good.substr(0, 100)); }, "shorter than the 127-byte header");
  expect_error([&] { pm::read_header(with_byte(good, 96, 2)); }, "clustered flag at byte 96");
  expect_error([&] { pm::read_header(with_byte(good, 97, 9)); }, "compression enum at byte 97");
  expect_error([&] { pm::read_header(with_byte(with_byte(good, 100, 5), 101, 4)); },
               "max zoom 4 (byte 101) is below min zoom 5");
}

TEST(SpecReaders, PmtilesSectionsOutOfBoundsThrow) {
  std::string tiles;
  const std::string good =
      build_archive(basic_header(), encode_directory(add_tiles(0, 5, tiles)), "{}", "", tiles);
  // Root directory length (byte 16) running past the end of the file.
  expect_error(
      [&] { pm::read_header(with_u64(good, 16, good.size())); },
      "root directory section [127, +" + std::to_string(good.size()) + ") is out of bounds");
  // Tile data offset (byte 56) so large that offset + length overflows.
  expect_error([&] { pm::read_header(with_u64(good, 56, UINT64_MAX)); }, "tile data section");
  expect_error([&] { pm::read_header(with_u64(good, 32, 1000)); }, "metadata section");
  expect_error([&] { pm::read_header(with_u64(with_u64(good, 40, good.size()), 48, 1)); },
               "leaf directories section");
  expect_error([&] { pm::read_header(with_u64(good, 16, 0)); }, "root directory length is 0");
  // Truncating the file cuts the tile data section.
  expect_error([&] { pm::read_header(good.substr(0, good.size() - 1)); }, "tile data section");
}

TEST(SpecReaders, PmtilesRootDirectoryBeyond16KiBThrows) {
  // Spec 4: header + root directory must fit in 16,384 bytes.
  std::string tiles;
  const std::vector<pm::Entry> entries = add_tiles(0, 5000, tiles);
  const std::string root = encode_directory(entries);
  ASSERT_GT(127 + root.size(), 16384u);
  const std::string file = build_archive(basic_header(), root, "{}", "", tiles);
  expect_error([&] { pm::read_header(file); }, "beyond the first 16384 bytes");
  // The same root fits once gzip-compressed.
  const std::string small = encode_directory(entries, pm::Compression::Gzip);
  ASSERT_LE(127 + small.size(), 16384u);
  EXPECT_EQ(pm::read_all_entries(
                build_archive(basic_header(pm::Compression::Gzip), small, gzip("{}"), "", tiles)),
            entries);
}

TEST(SpecReaders, PmtilesMalformedDirectoriesThrow) {
  const auto decode = [](const std::string& bytes) {
    pm::decode_directory(bytes, pm::Compression::None, "test directory");
  };
  // Entry count 0 (spec 4.2: MUST be > 0).
  expect_error([&] { decode(std::string(1, '\0')); }, "number of entries is 0");
  // Non-increasing tile ids: second delta 0.
  expect_error([&] { decode(std::string("\x02\x05\x00\x01\x01\x01\x01\x01\x00", 9)); },
               "non-increasing tile ids: entry 1 repeats tile id 5");
  // Length 0 (spec 4.1: MUST be > 0).
  expect_error([&] { decode(std::string("\x01\x00\x01\x00\x01", 5)); }, "length 0 of entry 0");
  // Truncated: the offset varint is missing / cut inside a continuation byte.
  expect_error([&] { decode(std::string("\x01\x00\x01\x05", 4)); },
               "truncated varint for an offset at byte 4");
  expect_error([&] { decode(std::string("\x01\x00\x01\x05\x81", 5)); },
               "truncated varint for an offset at byte 4");
  // First offset encoded as 0 ("same as previous") with no previous entry.
  expect_error([&] { decode(std::string("\x01\x00\x01\x05\x00", 5)); },
               "first entry's offset is encoded as 0");
  // Trailing bytes.
  expect_error([&] { decode(std::string("\x01\x00\x01\x05\x01\x07", 6)); },
               "1 trailing bytes after the last offset (at byte 5)");
  // Corrupt / truncated gzip.
  const std::string zipped = gzip(std::string("\x01\x00\x01\x05\x01", 5));
  expect_error(
      [&] { pm::decode_directory(zipped.substr(0, zipped.size() - 4), pm::Compression::Gzip); },
      "gzip data truncated");
  // Brotli / zstd are outside this reader.
  expect_error([&] { pm::decode_directory("\x01", pm::Compression::Brotli); },
               "compression 3 is not supported");
}

TEST(SpecReaders, PmtilesTileOutsideTileDataThrows) {
  std::string tiles;
  std::vector<pm::Entry> entries = add_tiles(0, 3, tiles);
  entries[2].length += 1;  // one byte past the tile data section
  const std::string file =
      build_archive(basic_header(), encode_directory(entries), "{}", "", tiles);
  expect_error([&] { pm::read_all_entries(file); },
               "tile data for tile id 2 at [" + std::to_string(entries[2].offset) + ", +" +
                   std::to_string(entries[2].length) +
                   ") is outside the tile data section of length " + std::to_string(tiles.size()));
  const pm::TileCoord c = pm::tile_id_to_zxy(2);
  expect_error([&] { pm::get_tile(file, c.z, c.x, c.y); }, "outside the tile data section");
  EXPECT_EQ(pm::get_tile(file, 0, 0, 0), std::optional<std::string>("tile 0/0/0"));
}

TEST(SpecReaders, PmtilesValidateArchiveChecksCountsAndClustering) {
  std::string tiles;
  const std::vector<pm::Entry> entries = add_tiles(0, 4, tiles);
  pm::Header h = basic_header();
  h.addressed_tiles_count = 5;
  expect_error(
      [&] { pm::validate_archive(build_archive(h, encode_directory(entries), "{}", "", tiles)); },
      "header number of addressed tiles (byte 72) is 5 but the directories give 4");
  h.addressed_tiles_count = 0;
  h.tile_contents_count = 3;
  expect_error(
      [&] { pm::validate_archive(build_archive(h, encode_directory(entries), "{}", "", tiles)); },
      "number of tile contents (byte 88) is 3");
  // Clustered: blobs in tile id order, no gaps. Swap two blobs -> a gap.
  h = basic_header();
  h.clustered = true;
  // Store the blob of id 2 before the blob of id 1: id 1 then starts after a gap.
  const std::string c0 = tile_content(0), c1 = tile_content(1), c2 = tile_content(2),
                    c3 = tile_content(3);
  const std::string reordered_tiles = c0 + c2 + c1 + c3;
  const auto len = [](const std::string& c) { return static_cast<std::uint32_t>(c.size()); };
  const std::vector<pm::Entry> reordered = {{0, 0, len(c0), 1},
                                            {1, c0.size() + c2.size(), len(c1), 1},
                                            {2, c0.size(), len(c2), 1},
                                            {3, c0.size() + c2.size() + c1.size(), len(c3), 1}};
  const std::string unclustered =
      build_archive(h, encode_directory(reordered), "{}", "", reordered_tiles);
  EXPECT_NO_THROW(pm::read_all_entries(unclustered));
  expect_error([&] { pm::validate_archive(unclustered); },
               "marked clustered but tile id 1 starts at offset");
}

// ---------------------------------------------------------------------------
// quantized-mesh-1.0: a tiny encoder written from the README.

struct TestMesh {
  double center[3] = {1, 2, 3};
  float min_height = -10.5f, max_height = 1234.25f;
  double sphere_center[3] = {4, 5, 6};
  double sphere_radius = 7;
  double horizon[3] = {0.5, 0.25, 0.125};
  std::vector<std::uint16_t> u, v, height;  // absolute quantized values
  std::vector<std::uint32_t> triangles;     // plain indices, new vertices in order
  std::vector<std::uint32_t> west, south, east, north;
  std::vector<std::pair<std::uint8_t, std::string>> extensions;
};

std::uint16_t zig_zag_encode(int delta) {
  // (delta << 1) ^ (delta >> 31), computed without shifting a negative value.
  return static_cast<std::uint16_t>((static_cast<std::uint32_t>(delta) << 1) ^
                                    (delta < 0 ? 0xffffffffu : 0u));
}

std::string encode_quantized_mesh(const TestMesh& m) {
  std::string out;
  for (double c : m.center)
    put_f64(out, c);
  put_f32(out, m.min_height);
  put_f32(out, m.max_height);
  for (double c : m.sphere_center)
    put_f64(out, c);
  put_f64(out, m.sphere_radius);
  for (double c : m.horizon)
    put_f64(out, c);
  put_uint(out, m.u.size(), 4);
  for (const auto* values : {&m.u, &m.v, &m.height}) {
    int previous = 0;
    for (std::uint16_t value : *values) {
      put_uint(out, zig_zag_encode(int(value) - previous), 2);
      previous = value;
    }
  }
  const int index_size = m.u.size() > 65536 ? 4 : 2;
  while (out.size() % index_size != 0)
    out.push_back('\0');
  put_uint(out, m.triangles.size() / 3, 4);
  std::uint32_t highest = 0;
  for (std::uint32_t index : m.triangles) {
    EXPECT_LE(index, highest) << "test encoder needs vertices in first-use order";
    if (index_size == 2) {
      EXPECT_LT(highest - index, 65536u) << "code does not fit 16 bits";
    }
    put_uint(out, highest - index, index_size);
    if (index == highest) ++highest;
  }
  for (const auto* edge : {&m.west, &m.south, &m.east, &m.north}) {
    put_uint(out, edge->size(), 4);
    for (std::uint32_t index : *edge)
      put_uint(out, index, index_size);
  }
  for (const auto& [id, data] : m.extensions) {
    out.push_back(static_cast<char>(id));
    put_uint(out, data.size(), 4);
    out += data;
  }
  return out;
}

// Octahedral encoding (Cigolle et al. 2014) to bytes 0..255, as the reader
// expects: project onto the octahedron, fold the lower hemisphere, map -1..1
// onto 0..255 with rounding.
std::pair<std::uint8_t, std::uint8_t> oct_encode(double x, double y, double z) {
  const double l1 = std::abs(x) + std::abs(y) + std::abs(z);
  double px = x / l1, py = y / l1;
  if (z < 0) {
    const double fx = (1 - std::abs(py)) * (px >= 0 ? 1 : -1);
    const double fy = (1 - std::abs(px)) * (py >= 0 ? 1 : -1);
    px = fx;
    py = fy;
  }
  auto to_byte = [](double p) {
    return static_cast<std::uint8_t>(std::lround((std::clamp(p, -1.0, 1.0) * 0.5 + 0.5) * 255));
  };
  return {to_byte(px), to_byte(py)};
}

std::string metadata_extension(const std::string& json) {
  std::string data;
  put_uint(data, json.size(), 4);
  return data + json;
}

// Two triangles covering the whole tile: SW(0), SE(1), NE(2), NW(3).
TestMesh two_triangle_tile() {
  TestMesh m;
  m.u = {0, 32767, 32767, 0};
  m.v = {0, 0, 32767, 32767};
  m.height = {0, 100, 32767, 16384};
  m.triangles = {0, 1, 2, 0, 2, 3};  // counter-clockwise in (u east, v north)
  m.west = {0, 3};
  m.south = {0, 1};
  m.east = {1, 2};
  m.north = {2, 3};
  return m;
}

TEST(SpecReaders, QuantizedMeshTwoTriangleTileDecodes) {
  TestMesh m = two_triangle_tile();
  const std::string normals = [] {
    std::string s;
    for (const auto& n : {std::array<double, 3>{0, 0, 1}, {1, 0, 0}, {0, -1, 0}, {0, 0, -1}}) {
      const auto [x, y] = oct_encode(n[0], n[1], n[2]);
      s.push_back(static_cast<char>(x));
      s.push_back(static_cast<char>(y));
    }
    return s;
  }();
  m.extensions = {{1, normals},
                  {2, std::string(1, '\xff')},
                  {4, metadata_extension("{\"available\":[]}")},
                  {9, "future"}};
  const std::string bytes = encode_quantized_mesh(m);
  const qm::Mesh mesh = qm::decode(bytes);

  EXPECT_EQ(mesh.header.center, (std::array<double, 3>{1, 2, 3}));
  EXPECT_EQ(mesh.header.min_height, -10.5f);
  EXPECT_EQ(mesh.header.max_height, 1234.25f);
  EXPECT_EQ(mesh.header.bounding_sphere_center, (std::array<double, 3>{4, 5, 6}));
  EXPECT_EQ(mesh.header.bounding_sphere_radius, 7);
  EXPECT_EQ(mesh.header.horizon_occlusion_point, (std::array<double, 3>{0.5, 0.25, 0.125}));
  EXPECT_EQ(mesh.u, m.u);
  EXPECT_EQ(mesh.v, m.v);
  EXPECT_EQ(mesh.height, m.height);
  EXPECT_EQ(mesh.triangles, m.triangles);
  EXPECT_FALSE(mesh.indices_are_32bit);
  EXPECT_EQ(mesh.index_padding_bytes, 0u);
  EXPECT_EQ(mesh.west_indices, m.west);
  EXPECT_EQ(mesh.south_indices, m.south);
  EXPECT_EQ(mesh.east_indices, m.east);
  EXPECT_EQ(mesh.north_indices, m.north);
  ASSERT_EQ(mesh.normals.size(), 4u);
  const std::array<double, 3> expected_normals[4] = {{0, 0, 1}, {1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
  for (int i = 0; i < 4; ++i) {
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(mesh.normals[i][c], expected_normals[i][c], 0.01);
  }
  ASSERT_TRUE(mesh.water_mask.has_value());
  EXPECT_EQ(*mesh.water_mask, std::vector<std::uint8_t>{255});
  EXPECT_EQ(mesh.metadata_json, std::optional<std::string>("{\"available\":[]}"));
  ASSERT_EQ(mesh.extensions.size(), 4u);
  EXPECT_EQ(mesh.extensions[3].id, 9);
  EXPECT_EQ(mesh.extensions[3].data, "future");
  EXPECT_NO_THROW(qm::validate_mesh(mesh));

  // Positions on the default geographic TMS grid: 0/1/0 is the eastern half.
  const qm::Rectangle rect = qm::geographic_tile_rectangle(0, 1, 0);
  EXPECT_EQ(rect.west, 0);
  EXPECT_EQ(rect.east, 180);
  EXPECT_EQ(rect.south, -90);
  EXPECT_EQ(rect.north, 90);
  const qm::Position ne = qm::decode_position(rect, mesh, 2);
  EXPECT_DOUBLE_EQ(ne.lon_deg, 180);
  EXPECT_DOUBLE_EQ(ne.lat_deg, 90);
  EXPECT_DOUBLE_EQ(ne.height_m, 1234.25);
  const qm::Position nw = qm::decode_position(rect, mesh, 3);
  EXPECT_DOUBLE_EQ(nw.lon_deg, 0);
  EXPECT_NEAR(nw.height_m, -10.5 + (1234.25 + 10.5) * 16384 / 32767.0, 1e-9);
  EXPECT_DOUBLE_EQ(qm::decode_position(rect, mesh, 0).height_m, -10.5);

  // The same tile gzip-compressed ("Terrain tiles are served gzipped").
  const qm::Mesh unzipped = qm::decode(gzip(bytes));
  EXPECT_EQ(unzipped.u, mesh.u);
  EXPECT_EQ(unzipped.triangles, mesh.triangles);
  EXPECT_EQ(unzipped.oct_normals, mesh.oct_normals);
  EXPECT_EQ(unzipped.metadata_json, mesh.metadata_json);
}

TEST(SpecReaders, QuantizedMeshRawBytesFollowTheReadme) {
  // Vertex deltas and index codes written out by hand rather than by the
  // encoder: u = 0, 32767, 32767, 0 -> deltas 0, +32767, 0, -32767 ->
  // zig-zag 0, 65534, 0, 65533. Triangles (0,1,2), (0,2,3) -> high-water
  // codes 0,0,0, 3,1,0.
  TestMesh m = two_triangle_tile();
  const std::string encoded = encode_quantized_mesh(m);
  std::string bytes = encoded.substr(0, 88);
  put_uint(bytes, 4, 4);
  for (int value : {0, 65534, 0, 65533, /*v*/ 0, 0, 65534, 0, /*h*/ 0, 200, 65334, 32765}) {
    put_uint(bytes, value, 2);
  }
  put_uint(bytes, 2, 4);
  for (int code : {0, 0, 0, 3, 1, 0})
    put_uint(bytes, code, 2);
  for (const std::vector<int>& edge : {std::vector<int>{0, 3}, {0, 1}, {1, 2}, {2, 3}}) {
    put_uint(bytes, edge.size(), 4);
    for (int index : edge)
      put_uint(bytes, index, 2);
  }
  EXPECT_EQ(bytes, encoded);
  const qm::Mesh mesh = qm::decode(bytes);
  EXPECT_EQ(mesh.u, m.u);
  EXPECT_EQ(mesh.v, m.v);
  EXPECT_EQ(mesh.height, m.height);
  EXPECT_EQ(mesh.triangles, m.triangles);
  EXPECT_TRUE(mesh.extensions.empty());
  EXPECT_FALSE(mesh.water_mask.has_value());
}

TEST(SpecReaders, QuantizedMeshIndexWidthAndPadding) {
  // 65537 vertices -> IndexData32 / EdgeIndices32. 88 + 4 + 6 * 65537 bytes is
  // 2 (mod 4), so 2 padding bytes precede the IndexData.
  TestMesh big;
  const std::uint32_t count = 65537;
  for (std::uint32_t i = 0; i < count; ++i) {
    big.u.push_back(static_cast<std::uint16_t>(i % 32768));
    big.v.push_back(static_cast<std::uint16_t>(i / 32768));
    big.height.push_back(static_cast<std::uint16_t>(i % 1000));
  }
  for (std::uint32_t i = 0; i + 2 < count; i += 3) {
    big.triangles.insert(big.triangles.end(), {i, i + 1, i + 2});
  }
  big.triangles.insert(big.triangles.end(), {65535, 65536, 0});
  big.west = {0, 32768, 65536};
  big.north = {65536};
  const qm::Mesh mesh = qm::decode(encode_quantized_mesh(big));
  EXPECT_TRUE(mesh.indices_are_32bit);
  EXPECT_EQ(mesh.index_padding_bytes, 2u);
  EXPECT_EQ(mesh.u, big.u);
  EXPECT_EQ(mesh.v, big.v);
  EXPECT_EQ(mesh.triangles, big.triangles);
  EXPECT_EQ(mesh.west_indices, big.west);
  EXPECT_EQ(mesh.north_indices, big.north);

  // Exactly 65536 vertices still uses 16-bit indices ("more than 65536").
  TestMesh edge = big;
  edge.u.pop_back();
  edge.v.pop_back();
  edge.height.pop_back();
  edge.triangles.resize(edge.triangles.size() - 3);
  // Vertex 0 can no longer be referenced here: its code, 65536 - 0, does not
  // fit in 16 bits. Vertex 1 (code 65535) can.
  edge.triangles.insert(edge.triangles.end(), {65535, 1, 2});
  edge.west = {0, 32768};
  edge.north = {};
  const qm::Mesh small = qm::decode(encode_quantized_mesh(edge));
  EXPECT_FALSE(small.indices_are_32bit);
  EXPECT_EQ(small.triangles, edge.triangles);
  EXPECT_EQ(small.west_indices, edge.west);
}

TEST(SpecReaders, QuantizedMeshWaterMaskGrid) {
  TestMesh m = two_triangle_tile();
  std::string grid(256 * 256, '\0');
  for (std::size_t i = 0; i < grid.size(); ++i)
    grid[i] = static_cast<char>(i % 256);
  m.extensions = {{2, grid}};
  const qm::Mesh mesh = qm::decode(encode_quantized_mesh(m));
  ASSERT_TRUE(mesh.water_mask.has_value());
  ASSERT_EQ(mesh.water_mask->size(), 65536u);
  EXPECT_EQ((*mesh.water_mask)[0], 0);
  EXPECT_EQ((*mesh.water_mask)[65535], 255);
  EXPECT_TRUE(mesh.normals.empty());
  EXPECT_FALSE(mesh.metadata_json.has_value());
}

TEST(SpecReaders, QuantizedMeshOctDecode) {
  // The six axes.
  const std::array<double, 3> axes[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                         {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  for (const auto& a : axes) {
    const auto [x, y] = oct_encode(a[0], a[1], a[2]);
    const auto n = qm::oct_decode(x, y);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(n[c], a[c], 0.01) << x << "," << y;
  }
  // Corners of the byte square all unfold to -z; byte 255 is exactly +1.
  EXPECT_NEAR(qm::oct_decode(0, 0)[2], -1, 1e-12);
  EXPECT_NEAR(qm::oct_decode(255, 255)[2], -1, 1e-12);
  EXPECT_NEAR(qm::oct_decode(255, 128)[0], 1, 1e-4);
  // Random directions: unit length, within a byte's quantization of the input.
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  for (int i = 0; i < 2000; ++i) {
    double v[3] = {normal(rng), normal(rng), normal(rng)};
    const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (double& c : v)
      c /= len;
    const auto [x, y] = oct_encode(v[0], v[1], v[2]);
    const auto n = qm::oct_decode(x, y);
    EXPECT_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0, 1e-12);
    const double dot = n[0] * v[0] + n[1] * v[1] + n[2] * v[2];
    EXPECT_GT(dot, std::cos(0.02)) << v[0] << " " << v[1] << " " << v[2];
  }
}

TEST(SpecReaders, QuantizedMeshMalformedThrows) {
  const TestMesh good = two_triangle_tile();
  const std::string bytes = encode_quantized_mesh(good);
  ASSERT_NO_THROW(qm::decode(bytes));
  expect_error([&] { qm::decode(bytes.substr(0, 50)); }, "shorter than the 88-byte header");
  expect_error([&] { qm::decode(bytes.substr(0, 100)); }, "truncated vertex data (4 vertices)");
  expect_error([&] { qm::decode(bytes.substr(0, bytes.size() - 1)); }, "truncated northIndices");
  expect_error([&] { qm::decode(bytes + "abc"); },
               "3 trailing bytes at byte " + std::to_string(bytes.size()));
  // A u delta that leaves 0..32767: first u = -1 (zig-zag 1).
  expect_error([&] { qm::decode(with_byte(bytes, 92, 1)); }, "vertex 0: decoded u = -1");
  // High-water-mark code above the mark: first code 1 at byte 88 + 4 + 24 + 4 = 120.
  expect_error([&] { qm::decode(with_byte(bytes, 120, 1)); },
               "high-water-mark code 1 at byte 120 exceeds the current high-water mark 0");
  // Edge index >= vertexCount: west count at 132, first west index at 136.
  expect_error([&] { qm::decode(with_byte(bytes, 136, 4)); },
               "westIndices[0] = 4 is not below the vertex count 4");
  // Bad extensions.
  TestMesh m = good;
  m.extensions = {{2, "abc"}};
  expect_error([&] { qm::decode(encode_quantized_mesh(m)); }, "length 3, expected 1 or 65536");
  m.extensions = {{1, "abc"}};
  expect_error([&] { qm::decode(encode_quantized_mesh(m)); },
               "length 3, expected 8 (2 bytes per vertex)");
  m.extensions = {{4, metadata_extension("{}") + "x"}};
  expect_error([&] { qm::decode(encode_quantized_mesh(m)); },
               "jsonLength 2 does not match the extension length 7 - 4");
  m.extensions = {{2, "\x01"}, {2, "\x01"}};
  expect_error([&] { qm::decode(encode_quantized_mesh(m)); }, "extension id appears twice");
  std::string cut = encode_quantized_mesh(m);
  cut.resize(cut.size() - 1);
  expect_error([&] { qm::decode(cut); }, "truncated extension 2");
  // A corrupt gzip stream.
  const std::string zipped = gzip(bytes);
  expect_error([&] { qm::decode(zipped.substr(0, zipped.size() / 2)); }, "gzip data truncated");

  // validate_mesh: edge lists and winding.
  qm::Mesh mesh = qm::decode(bytes);
  qm::Mesh wrong_edge = mesh;
  wrong_edge.west_indices = {0, 1};
  expect_error([&] { qm::validate_mesh(wrong_edge); },
               "west edge lists vertex 1 whose coordinate is 32767, not 0");
  qm::Mesh missing_edge = mesh;
  missing_edge.north_indices = {2};
  expect_error([&] { qm::validate_mesh(missing_edge); },
               "vertex 3 lies on the north edge but is missing from its edge list");
  TestMesh clockwise = good;
  clockwise.triangles = {0, 1, 2, 0, 3, 2};
  expect_error([&] { qm::validate_mesh(qm::decode(encode_quantized_mesh(clockwise))); },
               "triangle 1 (0, 3, 2) is clockwise");
}

TEST(SpecReaders, QuantizedMeshGeodeticHelpers) {
  const double a = 6378137.0, b = 6356752.314245179;
  auto near = [](const std::array<double, 3>& p, double x, double y, double z) {
    EXPECT_NEAR(p[0], x, 1e-6);
    EXPECT_NEAR(p[1], y, 1e-6);
    EXPECT_NEAR(p[2], z, 1e-6);
  };
  near(qm::ecef_from_geodetic(0, 0, 0), a, 0, 0);
  near(qm::ecef_from_geodetic(90, 0, 0), 0, a, 0);
  near(qm::ecef_from_geodetic(180, 0, 100), -(a + 100), 0, 0);
  near(qm::ecef_from_geodetic(0, 90, 0), 0, 0, b);
  near(qm::ecef_from_geodetic(0, -90, 10), 0, 0, -(b + 10));
  // At 45 degrees: N = a / sqrt(1 - e^2 / 2); X = N cos 45, Y = 0, Z = N (1 - e^2) sin 45.
  const double e2 = 6.69437999014e-3;
  const double n45 = a / std::sqrt(1 - e2 / 2);
  near(qm::ecef_from_geodetic(0, 45, 0), n45 * std::sqrt(0.5), 0, n45 * (1 - e2) * std::sqrt(0.5));

  const qm::Rectangle r{10, 20, 30, 60};
  const qm::Position mid = qm::decode_position(r, 16384, 8192, 32767, 100, 300);
  EXPECT_NEAR(mid.lon_deg, 10 + 20 * 16384 / 32767.0, 1e-12);
  EXPECT_NEAR(mid.lat_deg, 20 + 40 * 8192 / 32767.0, 1e-12);
  EXPECT_DOUBLE_EQ(mid.height_m, 300);
  near(mid.ecef(), qm::ecef_from_geodetic(mid.lon_deg, mid.lat_deg, 300)[0],
       qm::ecef_from_geodetic(mid.lon_deg, mid.lat_deg, 300)[1],
       qm::ecef_from_geodetic(mid.lon_deg, mid.lat_deg, 300)[2]);
  // slippyMap scheme counts rows from the north.
  const qm::Rectangle s = qm::geographic_tile_rectangle(1, 3, 0, /*tms=*/false);
  EXPECT_EQ(s.west, 90);
  EXPECT_EQ(s.east, 180);
  EXPECT_EQ(s.north, 90);
  EXPECT_EQ(s.south, 0);
}

// ---------------------------------------------------------------------------
// RGB-encoded DEM pixels and the Web Mercator grid.

TEST(SpecReaders, RasterDemPixelHeights) {
  EXPECT_EQ(dem::terrarium_height(128, 0, 0), 0.0);
  EXPECT_EQ(dem::terrarium_height(0, 0, 0), -32768.0);
  EXPECT_EQ(dem::terrarium_height(127, 255, 128), -0.5);
  EXPECT_EQ(dem::terrarium_height(139, 17, 64), 2833.25);  // 35601 + 0.25 - 32768
  EXPECT_EQ(dem::terrarium_height(255, 255, 255), 32767.0 + 255.0 / 256.0);
  EXPECT_NEAR(dem::terrain_rgb_height(1, 134, 160), 0.0, 1e-9);  // 100000 * 0.1 = 10000
  EXPECT_NEAR(dem::terrain_rgb_height(0, 0, 0), -10000.0, 1e-9);
  EXPECT_NEAR(dem::terrain_rgb_height(1, 150, 80), 401.6, 1e-9);  // 104016 * 0.1 - 10000
  // An RGBA 2x2 image: pixel (1, 1) is the last one.
  const std::uint8_t rgba[16] = {0, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0, 255, 128, 1, 128, 255};
  EXPECT_EQ(dem::pixel_height(rgba, 2, 2, 4, 1, 1, dem::Encoding::Terrarium), 1.5);
  EXPECT_NEAR(dem::pixel_height(rgba, 2, 2, 4, 1, 1, dem::Encoding::TerrainRgb),
              -10000 + (128 * 65536 + 256 + 128) * 0.1, 1e-9);
  expect_error([&] { dem::pixel_height(rgba, 2, 2, 4, 2, 0, dem::Encoding::Terrarium); },
               "pixel (2, 0) is outside the 2x2 image");
}

TEST(SpecReaders, WebMercatorPixelCentres) {
  // Zoom 0, 256 px: pixel (0, 0) centre is half a pixel in from the NW corner.
  const dem::LonLat nw = dem::pixel_center_lon_lat(0, 0, 0, 0, 0, 256);
  EXPECT_DOUBLE_EQ(nw.lon_deg, -180 + 0.5 * 360 / 256);
  EXPECT_NEAR(nw.lat_deg, std::atan(std::sinh(dem::kPi * (1 - 2 * 0.5 / 256))) * 180 / dem::kPi,
              1e-12);
  EXPECT_LT(nw.lat_deg, dem::kMaxMercatorLatitude);
  // Zoom 1, 512 px: the SE pixel of tile (0, 0) touches the centre of the world.
  const dem::LonLat c = dem::pixel_center_lon_lat(1, 0, 0, 511, 511, 512);
  EXPECT_NEAR(c.lon_deg, -0.5 * 360 / 1024, 1e-12);
  EXPECT_GT(c.lat_deg, 0);
  EXPECT_LT(c.lat_deg, 0.36);
  // Tile corners.
  EXPECT_NEAR(dem::lon_lat_from_tile_coords(0, 0, 0).lat_deg, dem::kMaxMercatorLatitude, 1e-9);
  EXPECT_NEAR(dem::lon_lat_from_tile_coords(3, 4, 4).lat_deg, 0, 1e-12);
  EXPECT_NEAR(dem::lon_lat_from_tile_coords(3, 8, 8).lon_deg, 180, 1e-12);
  // Known tile: Zurich (8.54, 47.37) at zoom 12 is tile 2145/1434 (OSM wiki formula).
  const dem::TilePixel z = dem::tile_pixel_from_lon_lat(12, 8.54, 47.37, 256);
  EXPECT_EQ(z.x, 2145u);
  EXPECT_EQ(z.y, 1434u);
  // World edges fall in the last column / row; beyond the square is an error.
  const dem::TilePixel se = dem::tile_pixel_from_lon_lat(2, 180, -dem::kMaxMercatorLatitude, 512);
  EXPECT_EQ(se.x, 3u);
  EXPECT_EQ(se.y, 3u);
  EXPECT_EQ(se.px, 511);
  EXPECT_EQ(se.py, 511);
  expect_error([] { dem::tile_pixel_from_lon_lat(2, 0, 86, 256); }, "outside the Web Mercator");
}

TEST(SpecReaders, WebMercatorRoundTrip) {
  std::mt19937 rng(11);
  for (int tile_size : {256, 512}) {
    for (int z = 0; z <= 12; ++z) {
      std::uniform_int_distribution<std::uint32_t> tile(0, (1u << z) - 1);
      std::uniform_int_distribution<int> pixel(0, tile_size - 1);
      for (int i = 0; i < 200; ++i) {
        const std::uint32_t x = tile(rng), y = tile(rng);
        const int px = pixel(rng), py = pixel(rng);
        const dem::LonLat ll = dem::pixel_center_lon_lat(z, x, y, px, py, tile_size);
        const dem::TilePixel back =
            dem::tile_pixel_from_lon_lat(z, ll.lon_deg, ll.lat_deg, tile_size);
        ASSERT_EQ(back.x, x);
        ASSERT_EQ(back.y, y);
        ASSERT_EQ(back.px, px);
        ASSERT_EQ(back.py, py);
      }
    }
  }
}

}  // namespace
