// The line pipeline's parts: geometry helpers, cutting into tiles, and the
// external sort (spilled or not, the same order).
#include <gtest/gtest.h>

#include <random>

#include "lines/line_geometry.hpp"
#include "lines/line_projector.hpp"
#include "test_support.hpp"
#include "tiles/tile_cutter.hpp"
#include "tiles/tile_sorter.hpp"

namespace {

using globe::XY;

TEST(LineGeometry, CleanPartDropsRepeatsAndFlagsBadParts) {
  std::vector<XY> p{{0, 0}, {0, 0}, {1, 1}, {1, 1}, {2, 0}};
  EXPECT_EQ(globe::clean_part(p), globe::PartStatus::kOk);
  EXPECT_EQ(p.size(), 3u);
  std::vector<XY> same{{5, 5}, {5, 5}, {5, 5}};
  EXPECT_EQ(globe::clean_part(same), globe::PartStatus::kDegenerate);
  std::vector<XY> nan{{0, 0}, {std::nan(""), 1}};
  EXPECT_EQ(globe::clean_part(nan), globe::PartStatus::kNonFinite);
}

TEST(LineGeometry, DouglasPeuckerStaysWithinTolerance) {
  std::mt19937 rng(1);
  std::normal_distribution<double> wiggle(0, 3);
  std::vector<XY> line;
  for (int i = 0; i < 500; ++i)
    line.push_back({double(i), 20 * std::sin(i / 30.0) + wiggle(rng)});
  for (double tol : {0.5, 2.0, 8.0}) {
    const auto s = globe::douglas_peucker(line, tol);
    EXPECT_EQ(s.front(), line.front());
    EXPECT_EQ(s.back(), line.back());
    EXPECT_LT(s.size(), line.size());
    // Every input vertex lies within tol of the simplified line.
    for (const XY& p : line) {
      double best = 1e9;
      for (size_t i = 0; i + 1 < s.size(); ++i) {
        const double dx = s[i + 1].x - s[i].x, dy = s[i + 1].y - s[i].y;
        double t = ((p.x - s[i].x) * dx + (p.y - s[i].y) * dy) / (dx * dx + dy * dy);
        t = std::clamp(t, 0.0, 1.0);
        best = std::min(best, std::hypot(p.x - s[i].x - t * dx, p.y - s[i].y - t * dy));
      }
      EXPECT_LE(best, tol + 1e-9);
    }
  }
}

TEST(LineGeometry, ClipSegment) {
  XY a{-5, 5}, b{15, 5};
  double t0, t1;
  ASSERT_TRUE(globe::clip_segment(a, b, {0, 0, 10, 10}, &t0, &t1));
  EXPECT_EQ(a, (XY{0, 5}));
  EXPECT_EQ(b, (XY{10, 5}));
  EXPECT_DOUBLE_EQ(t0, 0.25);
  EXPECT_DOUBLE_EQ(t1, 0.75);
  XY c{-5, -5}, d{-1, 20};
  EXPECT_FALSE(globe::clip_segment(c, d, {0, 0, 10, 10}));
}

TEST(LineGeometry, AntimeridianCrossingIsCutAtTheCrossingLatitude) {
  const std::vector<XY> line{{170, 10}, {-170, 20}, {-160, 20}};
  const auto parts = globe::split_antimeridian(line);
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0].back(), (XY{180, 15}));
  EXPECT_EQ(parts[1].front(), (XY{-180, 15}));
  EXPECT_EQ(parts[1].back(), (XY{-160, 20}));
  // The other way round; longitudes beyond 180 are wrapped first.
  const auto west = globe::split_antimeridian(std::vector<XY>{{-175, 0}, {175, 10}});
  ASSERT_EQ(west.size(), 2u);
  EXPECT_EQ(west[0].back().x, -180);
  EXPECT_EQ(west[1].front().x, 180);
  EXPECT_EQ(globe::split_antimeridian(std::vector<XY>{{10, 0}, {20, 0}}).size(), 1u);
  const auto wrapped = globe::split_antimeridian(std::vector<XY>{{170, 0}, {185, 0}});
  ASSERT_EQ(wrapped.size(), 2u);
  EXPECT_EQ(wrapped[1].back(), (XY{-175, 0}));
}

TEST(LineProjector, PointsWrapLongitudeAndLinesAreCutAtTheAntimeridian) {
  const auto wgs84 = globe::SpatialRef::from_user_input("EPSG:4326", "test");
  const globe::LineProjector geodetic(globe::TargetFrame::kGeodetic, wgs84, nullptr);
  XY p;
  ASSERT_TRUE(geodetic.project_point({190, 10}, p));
  EXPECT_NEAR(p.x, -170, 1e-9);
  EXPECT_NEAR(p.y, 10, 1e-9);
  std::vector<std::vector<XY>> out;
  globe::ProjectionCounts counts;
  geodetic.project_lines({{{170, 0}, {-170, 0}}, {{1, 1}, {1, 1}}}, out, counts);
  EXPECT_EQ(out.size(), 2u);
  EXPECT_EQ(counts.antimeridian_cuts, 1u);
  EXPECT_EQ(counts.degenerate_parts, 1u);
  const globe::LineProjector mercator(globe::TargetFrame::kWebMercator, wgs84, nullptr);
  ASSERT_TRUE(mercator.project_point({180, 89}, p));  // latitude clamped to 85.0511
  EXPECT_NEAR(p.x, 20037508.342789244, 1e-6);
  EXPECT_NEAR(p.y, 20037508.342789244, 1e-3);
}

TEST(TileCutter, LinesContinueAcrossTileBordersAndStayInOneRunPerTile) {
  const auto tiling = tileformat::Tiling::local("EPSG:3857", 0, 1024, 1024);  // z1: 512 tiles
  const globe::TileCutter cutter(tiling, 4096, 0, tiling.extent());
  globe::ProjectedFeature f;
  f.id = 1;
  f.lines = {{{100, 700}, {300, 700}, {700, 700}, {900, 300}}};  // crosses x = 512, then y = 512
  std::vector<globe::Emission> out;
  globe::CutStats stats;
  uint32_t sub = 0;
  cutter.cut(f, 1, 32, globe::Collapsed::kDrop, sub, out, stats);
  std::map<std::string, std::vector<tileformat::LineVertex>> by_tile;
  for (const auto& e : out)
    by_tile[globe::key_tile(e.key).str()] = e.piece.vertices;
  ASSERT_EQ(by_tile.size(), 3u);  // (0,0) (1,0) (1,1)
  // Tile 1/0/0 (x 0..512, y 512..1024): the line enters at (100,700) and
  // leaves through the widened east edge, one run; the shared vertex at
  // x = 300 is exact: 300 / 512 * 4096 = 2400, y = (1024-700)/512*4096 = 2592.
  const auto& west = by_tile.at("1/0/0");
  EXPECT_EQ(west[0], (tileformat::LineVertex{800, 2592}));
  EXPECT_EQ(west[1], (tileformat::LineVertex{2400, 2592}));
  EXPECT_EQ(west.size(), 3u);
  EXPECT_EQ(west[2].x, 4096 + 34);  // clipped at the margin: reach 32 + 2
  // In tile 1/1/0 the same line starts inside the west margin.
  EXPECT_EQ(by_tile.at("1/1/0").front().x, -34);
  EXPECT_EQ(stats.runs, 3u);
}

TEST(TileCutter, FeaturesBelowOneGridStepBecomeDotsOnlyAtTheFinestZoom) {
  const auto tiling = tileformat::Tiling::local("EPSG:3857", 0, 1024, 1024);
  const globe::TileCutter cutter(tiling, 4096, 0, tiling.extent());
  globe::ProjectedFeature f;
  f.id = 1;
  f.lines = {{{100.01, 700.01}, {100.02, 700.02}}};  // far below 1/8 unit at zoom 0
  std::vector<globe::Emission> out;
  globe::CutStats stats;
  uint32_t sub = 0;
  cutter.cut(f, 0, 16, globe::Collapsed::kDrop, sub, out, stats);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(stats.collapsed_runs, 1u);
  cutter.cut(f, 0, 16, globe::Collapsed::kKeep, sub, out, stats);
  ASSERT_EQ(out.size(), 1u);
  ASSERT_EQ(out[0].piece.vertices.size(), 2u);
  EXPECT_EQ(out[0].piece.vertices[0], out[0].piece.vertices[1]);
}

TEST(TileCutter, PiecesSurviveTheScratchRoundTrip) {
  globe::TilePiece p{false, 42, {{-3, 4}, {5000, -70}}};
  const auto q = globe::TilePiece::from_bytes(p.to_bytes());
  EXPECT_EQ(q.class_id, 42u);
  EXPECT_EQ(q.vertices, p.vertices);
  EXPECT_EQ(globe::key_tile(globe::tile_key({13, 8191, 77})), (tileformat::TileId{13, 8191, 77}));
}

// Records come back grouped by key in (key, seq, sub) order, whether they
// stayed in memory or were spilled to many run files.
TEST(TileSorter, SpilledAndInMemorySortsAgree) {
  globe_test::TempDir dir;
  auto fill = [](globe::TileSorter& s) {
    std::mt19937 rng(2);
    for (int i = 0; i < 20000; ++i) {
      std::vector<uint8_t> payload(rng() % 40, static_cast<uint8_t>(i));
      s.add(rng() % 300, rng() % 1000, static_cast<uint32_t>(i),
            payload);  // (key, seq, sub) unique, as in a build
    }
    s.finish();
  };
  globe::TileSorter mem((dir / "a").string(), 1 << 30), disk((dir / "b").string(), 1);
  fill(mem);
  fill(disk);
  EXPECT_EQ(mem.spilled_runs(), 0u);
  EXPECT_GT(disk.spilled_runs(), 3u);
  uint64_t last = 0, groups = 0;
  globe::TileGroup g1, g2;
  while (mem.next_group(g1)) {
    ASSERT_TRUE(disk.next_group(g2));
    ASSERT_EQ(g1.key, g2.key);
    EXPECT_GE(g1.key, last);
    last = g1.key;
    ASSERT_EQ(g1.records.size(), g2.records.size());
    for (size_t i = 0; i < g1.records.size(); ++i) {
      const auto &a = g1.records[i], &b = g2.records[i];
      EXPECT_EQ(a.seq, b.seq);
      EXPECT_EQ(a.sub, b.sub);
      EXPECT_TRUE(std::ranges::equal(g1.payload(a), g2.payload(b)));
      if (i) {
        EXPECT_LE(std::tie(g1.records[i - 1].seq, g1.records[i - 1].sub), std::tie(a.seq, a.sub));
      }
    }
    ++groups;
  }
  EXPECT_FALSE(disk.next_group(g2));
  EXPECT_EQ(groups, 300u);
}

}  // namespace
