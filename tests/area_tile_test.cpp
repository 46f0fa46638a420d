// Area tile codec (docs/tileformat.md §12): round trip, and every invariant
// the encoder and decoder enforce, with blobs built by hand.
#include <gtest/gtest.h>

#include "tileformat/area_tile.hpp"
#include "tileformat/error.hpp"

namespace {

using tileformat::AreaTile;

// A square with a square hole (feature 3) and a triangle reaching into the
// buffer (feature 9); exteriors clockwise on screen (y down), the hole not.
AreaTile sample() {
  AreaTile t;
  t.buffer = 64;
  t.feature_ids = {3, 9};
  t.polygons = {{0, 1, 0, 2}, {1, 0, 2, 1}};
  t.ring_sizes = {4, 4, 3};
  t.vertices = {{0, 0},       {4000, 0},    {4000, 4000}, {0, 4000},   {1000, 1000}, {1000, 3000},
                {3000, 3000}, {3000, 1000}, {4100, -50},  {4150, 200}, {3900, 100}};
  return t;
}

TEST(AreaTile, RoundTripsAndPeeksItsCounts) {
  const AreaTile t = sample();
  const std::vector<uint8_t> blob = tileformat::encode_area_tile(t);
  const AreaTile u = tileformat::decode_area_tile(blob);
  EXPECT_EQ(u.extent, t.extent);
  EXPECT_EQ(u.buffer, t.buffer);
  EXPECT_EQ(u.feature_ids, t.feature_ids);
  ASSERT_EQ(u.polygons.size(), 2u);
  EXPECT_EQ(u.polygons[0].class_id, 1u);
  EXPECT_EQ(u.polygons[1].feature, 1u);
  EXPECT_EQ(u.ring_sizes, t.ring_sizes);
  EXPECT_EQ(u.vertices, t.vertices);
  const auto c = tileformat::peek_area_tile_counts(blob);
  EXPECT_EQ(c.features, 2u);
  EXPECT_EQ(c.polygons, 2u);
  EXPECT_EQ(c.rings, 3u);
  EXPECT_EQ(c.vertices, 11u);
}

TEST(AreaTile, RingAreaIsPositiveForClockwiseOnScreen) {
  const AreaTile t = sample();
  EXPECT_GT(tileformat::ring_area2({t.vertices.data(), 4}), 0);
  EXPECT_LT(tileformat::ring_area2({t.vertices.data() + 4, 4}), 0);
  // 2 x the square's 4000 x 4000.
  EXPECT_EQ(tileformat::ring_area2({t.vertices.data(), 4}), 2 * 4000ll * 4000);
}

TEST(AreaTile, EncoderRefusesBrokenTiles) {
  auto refuses = [](AreaTile t) {
    EXPECT_THROW(tileformat::encode_area_tile(t), tileformat::FormatError);
  };
  AreaTile t = sample();
  std::reverse(t.vertices.begin(), t.vertices.begin() + 4);  // exterior counter-clockwise
  refuses(t);
  t = sample();
  std::reverse(t.vertices.begin() + 4, t.vertices.begin() + 8);  // hole clockwise
  refuses(t);
  t = sample();
  t.vertices[8] = {4200, -50};  // past the 64-unit buffer
  refuses(t);
  t = sample();
  t.ring_sizes = {4, 4, 2, 1};  // a ring of 2
  t.polygons[1].ring_count = 2;
  refuses(t);
  t = sample();
  t.polygons[1].feature = 2;  // no such feature
  refuses(t);
  t = sample();
  t.polygons[0].ring_count = 1;  // the hole owned by nobody
  t.polygons[1].first_ring = 1;
  refuses(t);
}

TEST(AreaTile, DecoderRefusesDamagedBlobs) {
  std::vector<uint8_t> blob = tileformat::encode_area_tile(sample());
  for (size_t cut : {size_t(3), size_t(12), blob.size() - 1}) {
    const std::vector<uint8_t> part(blob.begin(), blob.begin() + static_cast<long>(cut));
    EXPECT_THROW(tileformat::decode_area_tile(part), tileformat::FormatError) << cut;
  }
  std::vector<uint8_t> bad = blob;
  bad[15] ^= 0xff;  // the extent: past 2^24
  EXPECT_THROW(tileformat::decode_area_tile(bad), tileformat::FormatError);
  bad = blob;
  bad[12 + 4 * 6] ^= 1;  // the payload's size: zstd finds another
  EXPECT_THROW(tileformat::decode_area_tile(bad), tileformat::FormatError);
  bad = blob;
  bad[12 + 4 * 5] += 1;  // one vertex more than the rings hold
  EXPECT_THROW(tileformat::decode_area_tile(bad), tileformat::FormatError);
}

TEST(AreaTile, AnEmptyTileRoundTrips) {
  const AreaTile u = tileformat::decode_area_tile(tileformat::encode_area_tile(AreaTile{}));
  EXPECT_TRUE(u.polygons.empty());
  EXPECT_TRUE(u.vertices.empty());
}

}  // namespace
