// Point tiles (tileformat §11): codec round trip, rejection of damaged
// blobs, the cluster-grid contract as a property on random places (checked
// by a brute force over pixels here), and the point metadata keys.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tileformat/error.hpp"
#include "tileformat/metadata.hpp"
#include "tileformat/point_tile.hpp"

namespace {

using tileformat::Place;
using tileformat::PointTile;

PointTile random_tile(std::mt19937& rng, uint32_t reach, uint32_t grid = 16, uint32_t fields = 3) {
  PointTile t;
  t.grid = grid;
  t.reach = reach;
  t.fields = fields;
  std::uniform_int_distribution<int32_t> coord(0, 4096);
  const int n = 1 + static_cast<int>(rng() % 60);
  uint64_t id = 1 + rng() % 10;
  for (int i = 0; i < n; ++i) {
    t.places.push_back({id,
                        1 + static_cast<uint32_t>(rng() % 3 == 0 ? rng() % 500 : 0),
                        {coord(rng), coord(rng)}});
    id += 1 + rng() % 100;
    for (uint32_t f = 0; f < fields; ++f)
      t.values.push_back(static_cast<float>(rng() % 100000) / 7.0f);
  }
  tileformat::build_point_grid(t);
  return t;
}

TEST(PointTile, RoundTripKeepsEverything) {
  std::mt19937 rng(7);
  for (int k = 0; k < 50; ++k) {
    const PointTile t = random_tile(rng, rng() % 400, 1u << (rng() % 6), 1 + rng() % 8);
    const auto blob = tileformat::encode_point_tile(t);
    const PointTile d = tileformat::decode_point_tile(blob);
    EXPECT_EQ(d.extent, t.extent);
    EXPECT_EQ(d.grid, t.grid);
    EXPECT_EQ(d.reach, t.reach);
    EXPECT_EQ(d.fields, t.fields);
    ASSERT_EQ(d.places.size(), t.places.size());
    for (size_t i = 0; i < t.places.size(); ++i) {
      EXPECT_EQ(d.places[i].id, t.places[i].id);
      EXPECT_EQ(d.places[i].count, t.places[i].count);
      EXPECT_EQ(d.places[i].at, t.places[i].at);
    }
    EXPECT_EQ(d.values, t.values);  // float32 bit for bit
    EXPECT_EQ(d.cell_offsets, t.cell_offsets);
    EXPECT_EQ(d.cell_places, t.cell_places);
    const auto counts = tileformat::peek_point_tile_counts(blob);
    EXPECT_EQ(counts.places, t.places.size());
    EXPECT_EQ(counts.fields, t.fields);
  }
}

TEST(PointTile, EveryTruncationAndTrailingByteIsRejected) {
  std::mt19937 rng(3);
  const auto blob = tileformat::encode_point_tile(random_tile(rng, 100));
  for (size_t n = 0; n < blob.size(); ++n) {
    std::vector<uint8_t> cut(blob.begin(), blob.begin() + n);
    EXPECT_THROW(tileformat::decode_point_tile(cut), tileformat::FormatError) << n;
  }
  auto longer = blob;
  longer.push_back(0);
  EXPECT_THROW(tileformat::decode_point_tile(longer), tileformat::FormatError);
}

TEST(PointTile, DamagedHeaderCountsAreRejectedNotTrusted) {
  std::mt19937 rng(5);
  const auto blob = tileformat::encode_point_tile(random_tile(rng, 100));
  // Each u32 of the §11.1 header (after the 12-byte blob header), set huge.
  for (size_t field = 0; field < 8; ++field) {
    auto bad = blob;
    for (int b = 0; b < 4; ++b)
      bad[12 + 4 * field + b] = 0xff;
    EXPECT_THROW(tileformat::decode_point_tile(bad), tileformat::FormatError) << "field " << field;
  }
}

TEST(PointTile, EncoderRefusesTilesBreakingInvariants) {
  std::mt19937 rng(9);
  PointTile t = random_tile(rng, 40);
  t.places.push_back({t.places.back().id, 1, {5, 5}});  // ids not increasing
  t.values.resize(t.places.size() * t.fields);
  tileformat::build_point_grid(t);
  EXPECT_THROW(tileformat::encode_point_tile(t), tileformat::FormatError);
  t = random_tile(rng, 40);
  t.places[0].at.x = 5000;  // outside the tile
  EXPECT_THROW(tileformat::encode_point_tile(t), tileformat::FormatError);
  t = random_tile(rng, 40);
  t.values.pop_back();
  EXPECT_THROW(tileformat::encode_point_tile(t), tileformat::FormatError);
  t = random_tile(rng, 40);
  t.cell_offsets.clear();
  EXPECT_THROW(tileformat::encode_point_tile(t), tileformat::FormatError);
}

// The §11.3 contract, against a brute force over every cell: a cell lists a
// place iff the distance from the place to the closed cell square is at most
// `reach`.
TEST(PointTile, GridListsExactlyThePlacesWithinReachOfEachCell) {
  std::mt19937 rng(11);
  for (int k = 0; k < 30; ++k) {
    const PointTile t = random_tile(rng, rng() % 700, std::array<uint32_t, 4>{1, 8, 16, 64}[k % 4]);
    const double cs = double(t.extent) / t.grid;
    for (uint32_t c = 0; c < t.grid * t.grid; ++c) {
      const double x0 = (c % t.grid) * cs, y0 = (c / t.grid) * cs;
      std::vector<uint32_t> expected;
      for (uint32_t i = 0; i < t.places.size(); ++i) {
        const double px = t.places[i].at.x, py = t.places[i].at.y;
        const double dx = std::max({x0 - px, 0.0, px - (x0 + cs)});
        const double dy = std::max({y0 - py, 0.0, py - (y0 + cs)});
        if (std::hypot(dx, dy) <= t.reach) expected.push_back(i);
      }
      const std::vector<uint32_t> listed(t.cell_places.begin() + t.cell_offsets[c],
                                         t.cell_places.begin() + t.cell_offsets[c + 1]);
      EXPECT_EQ(listed, expected) << "cell " << c << " of grid " << t.grid;
    }
  }
}

TEST(PointMetadata, RoundTripsAndRejectsBadKeys) {
  tileformat::PointMetadata m;
  m.common.format = tileformat::kPointsFormat;
  m.common.name = "p";
  m.common.lonlat = {-10, -5, 10, 5};
  m.common.max_zoom = 3;
  m.common.tiling = tileformat::Tiling::webmercator();
  m.extent = 4096;
  m.cluster_grid = 16;
  m.tile_px = 256;
  m.chart_max_px = 48;
  m.fields = {"a", "b \"quoted\""};
  m.aggregate = tileformat::PointAggregate::kMean;
  m.merge_px = 40;
  m.signed_values = true;
  m.label_field = "name";
  m.features = 12;
  m.zooms = {{0, 2, 10.5, 7.25}, {3, 12, 3.0, 2.0}};
  const auto meta = tileformat::to_metadata(m);
  const tileformat::PointMetadata r = tileformat::read_point_metadata(meta);
  EXPECT_EQ(r.fields, m.fields);
  EXPECT_EQ(r.aggregate, m.aggregate);
  EXPECT_TRUE(r.signed_values);
  EXPECT_EQ(r.label_field, "name");
  EXPECT_EQ(r.features, 12u);
  ASSERT_EQ(r.zooms.size(), 2u);
  EXPECT_EQ(r.zooms[0].max_total, 10.5);
  EXPECT_EQ(r.zooms[1].places, 12u);
  EXPECT_EQ(tileformat::package_kind_of_format(r.common.format), tileformat::PackageKind::kPoints);
  auto bad = meta;
  bad["globe:aggregate"] = "median";
  EXPECT_THROW(tileformat::read_point_metadata(bad), tileformat::FormatError);
  bad = meta;
  bad["globe:fields"] = "[]";
  EXPECT_THROW(tileformat::read_point_metadata(bad), tileformat::FormatError);
  bad = meta;
  bad["globe:zoom_stats"] = "[{\"zoom\":9,\"places\":1,\"max_total\":1,\"max_value\":1}]";
  EXPECT_THROW(tileformat::read_point_metadata(bad), tileformat::FormatError);
}

}  // namespace
