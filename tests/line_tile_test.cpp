// Line-cluster tiles (tileformat §7): codec round trip, rejection of damaged
// blobs, and the cluster-grid contract as a property on random segments.
#include <gtest/gtest.h>

#include <random>

#include "tileformat/error.hpp"
#include "tileformat/line_clusters.hpp"
#include "tileformat/line_tile.hpp"

namespace {

using tileformat::LineRun;
using tileformat::LineTile;
using tileformat::LineVertex;

// Random runs over a tile (vertices may reach past the tile edges, as the
// clipping margin allows), random points, grid built by the library.
LineTile random_tile(std::mt19937& rng, uint32_t reach, uint32_t grid = 32) {
  LineTile t;
  t.grid = grid;
  t.reach = reach;
  std::uniform_int_distribution<int32_t> coord(-200, 4296);
  std::uniform_int_distribution<int> nruns(1, 40), nverts(2, 12), step(-600, 600);
  const int runs = nruns(rng);
  for (int f = 0; f < runs; ++f)
    t.feature_ids.push_back(t.feature_ids.empty() ? 1 + rng() % 5
                                                  : t.feature_ids.back() + 1 + rng() % 1000);
  for (int r = 0; r < runs; ++r) {
    const int n = nverts(rng);
    LineRun run{static_cast<uint32_t>(r), static_cast<uint32_t>(rng() % 7),
                static_cast<uint32_t>(t.vertices.size()), static_cast<uint32_t>(n)};
    LineVertex v{coord(rng), coord(rng)};
    for (int i = 0; i < n; ++i) {
      t.vertices.push_back(v);
      v = {std::clamp(v.x + step(rng), -1000, 5000), std::clamp(v.y + step(rng), -1000, 5000)};
    }
    t.runs.push_back(run);
  }
  for (int i = 0; i < 5; ++i)
    t.points.push_back({static_cast<uint32_t>(rng() % runs), 1, {coord(rng), coord(rng)}});
  tileformat::build_cluster_grid(t);
  return t;
}

TEST(LineTile, RoundTripKeepsEverything) {
  std::mt19937 rng(7);
  for (int k = 0; k < 50; ++k) {
    const LineTile t = random_tile(rng, 16 + rng() % 200);
    const LineTile d = tileformat::decode_line_tile(tileformat::encode_line_tile(t));
    EXPECT_EQ(d.extent, t.extent);
    EXPECT_EQ(d.grid, t.grid);
    EXPECT_EQ(d.reach, t.reach);
    EXPECT_EQ(d.feature_ids, t.feature_ids);
    ASSERT_EQ(d.runs.size(), t.runs.size());
    for (size_t i = 0; i < t.runs.size(); ++i) {
      EXPECT_EQ(d.runs[i].feature, t.runs[i].feature);
      EXPECT_EQ(d.runs[i].class_id, t.runs[i].class_id);
      EXPECT_EQ(d.runs[i].vertex_count, t.runs[i].vertex_count);
    }
    EXPECT_EQ(d.vertices, t.vertices);
    ASSERT_EQ(d.points.size(), t.points.size());
    EXPECT_EQ(d.points[3].at, t.points[3].at);
    EXPECT_EQ(d.cell_offsets, t.cell_offsets);
    EXPECT_EQ(d.cell_segments, t.cell_segments);
    const auto counts = tileformat::peek_line_tile_counts(tileformat::encode_line_tile(t));
    EXPECT_EQ(counts.segments, t.segment_count());
  }
}

TEST(LineTile, EveryTruncationAndTrailingByteIsRejected) {
  std::mt19937 rng(3);
  const auto blob = tileformat::encode_line_tile(random_tile(rng, 40));
  for (size_t n = 0; n < blob.size(); ++n) {
    std::vector<uint8_t> cut(blob.begin(), blob.begin() + n);
    EXPECT_THROW(tileformat::decode_line_tile(cut), tileformat::FormatError) << n;
  }
  auto longer = blob;
  longer.push_back(0);
  EXPECT_THROW(tileformat::decode_line_tile(longer), tileformat::FormatError);
}

TEST(LineTile, DamagedHeaderCountsAreRejectedNotTrusted) {
  std::mt19937 rng(5);
  const auto blob = tileformat::encode_line_tile(random_tile(rng, 40));
  // Each u32 of the §7.1 header (after the 12-byte blob header), set huge.
  for (size_t field = 0; field < 10; ++field) {
    auto bad = blob;
    for (int b = 0; b < 4; ++b)
      bad[12 + 4 * field + b] = 0xff;
    EXPECT_THROW(tileformat::decode_line_tile(bad), tileformat::FormatError) << "field " << field;
  }
}

TEST(LineTile, EncoderRefusesTilesBreakingInvariants) {
  std::mt19937 rng(9);
  LineTile t = random_tile(rng, 40);
  t.feature_ids.push_back(t.feature_ids.back());  // not strictly increasing
  EXPECT_THROW(tileformat::encode_line_tile(t), tileformat::FormatError);
  t = random_tile(rng, 40);
  t.cell_offsets.clear();  // grid not built
  EXPECT_THROW(tileformat::encode_line_tile(t), tileformat::FormatError);
}

// The §7.3 contract: (1) every point within `reach` of a segment lies in a
// cell that lists the segment; (2) no cell lists a segment whose footprint
// misses it.
TEST(LineClusters, GridIsCompleteAndTightOnRandomTiles) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  uint64_t checked_points = 0;
  for (int k = 0; k < 40; ++k) {
    const uint32_t grid = std::array<uint32_t, 4>{8, 16, 32, 64}[k % 4];
    const LineTile t = random_tile(rng, 8 + rng() % 300, grid);
    const auto segs = t.segments();
    const double cs = double(t.extent) / t.grid;
    for (size_t c = 0; c + 1 < t.cell_offsets.size(); ++c) {
      const double x0 = (c % t.grid) * cs, y0 = (c / t.grid) * cs;
      for (uint32_t e = t.cell_offsets[c]; e < t.cell_offsets[c + 1]; ++e) {
        const auto& s = segs[t.cell_segments[e]];
        EXPECT_LE(tileformat::segment_rect_distance(s.a, s.b, x0, y0, x0 + cs, y0 + cs), t.reach)
            << "cell " << c << " lists segment " << t.cell_segments[e] << " it cannot reach";
      }
    }
    for (size_t si = 0; si < segs.size(); ++si) {
      const auto& s = segs[si];
      for (int p = 0; p < 40; ++p) {
        // A point at distance <= reach from the segment.
        const double u = unit(rng), ang = unit(rng) * 6.283185307179586, r = unit(rng) * t.reach;
        const double px = s.a.x + u * (s.b.x - s.a.x) + r * std::cos(ang);
        const double py = s.a.y + u * (s.b.y - s.a.y) + r * std::sin(ang);
        if (px < 0 || py < 0 || px >= t.extent || py >= t.extent) continue;
        if (tileformat::point_segment_distance(px, py, s.a, s.b) > t.reach) continue;
        const uint32_t cell = t.cell_of(px, py);
        const auto begin = t.cell_segments.begin() + t.cell_offsets[cell];
        const auto end = t.cell_segments.begin() + t.cell_offsets[cell + 1];
        EXPECT_TRUE(std::binary_search(begin, end, static_cast<uint32_t>(si)))
            << "point (" << px << "," << py << ") within reach of segment " << si
            << " but its cell " << cell << " does not list it";
        ++checked_points;
      }
    }
  }
  EXPECT_GT(checked_points, 10000u);
}

TEST(LineClusters, SegmentRectDistance) {
  // Crossing the rectangle, touching a corner, beside an edge, past a corner.
  EXPECT_EQ(tileformat::segment_rect_distance({-10, 5}, {20, 5}, 0, 0, 10, 10), 0);
  EXPECT_EQ(tileformat::segment_rect_distance({10, 10}, {20, 20}, 0, 0, 10, 10), 0);
  EXPECT_DOUBLE_EQ(tileformat::segment_rect_distance({13, -5}, {13, 20}, 0, 0, 10, 10), 3);
  EXPECT_DOUBLE_EQ(tileformat::segment_rect_distance({13, 14}, {20, 14}, 0, 0, 10, 10), 5);
  // A diagonal passing a corner: distance from the corner to the line.
  EXPECT_NEAR(tileformat::segment_rect_distance({14, 2}, {2, -10}, 0, 0, 10, 10), std::sqrt(2.0),
              1e-12);
}

}  // namespace
