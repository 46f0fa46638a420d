// The area fill pass's words (viewer/data/area_cache.hpp): the winding number
// a pixel gets from its cell's reference point and the crossings to it equals
// a brute-force point-in-polygon test (even-odd over every ring, written
// here), for random polygons with holes, reaching into the buffer, at random
// points and at points on cell borders and corners.
#include <gtest/gtest.h>

#include <random>

#include "data/area_cache.hpp"

namespace {

using tileformat::AreaTile;
using tileformat::LineVertex;

// Even-odd: inside any exterior and in none of its holes (rings do not cross).
bool brute_inside(const std::vector<std::vector<LineVertex>>& rings, double x, double y) {
  bool in = false;
  for (const auto& r : rings)
    for (size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) {
      const double xi = r[i].x, yi = r[i].y, xj = r[j].x, yj = r[j].y;
      if ((yi > y) != (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi) in = !in;
    }
  return in;
}

// A star-shaped ring around (cx, cy): radii random, angles increasing.
std::vector<LineVertex> star(std::mt19937& rng, double cx, double cy, double r0, double r1, int n,
                             bool clockwise_on_screen) {
  std::uniform_real_distribution<double> u(r0, r1);
  std::vector<LineVertex> ring;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * 3.14159265358979 * i / n * (clockwise_on_screen ? 1 : -1);
    const double r = u(rng);
    ring.push_back(
        {int32_t(std::lround(cx + r * std::cos(a))), int32_t(std::lround(cy + r * std::sin(a)))});
  }
  return ring;
}

TEST(AreaWords, WindingMatchesABruteForcePointInPolygon) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    std::mt19937 rng(seed);
    AreaTile t;
    t.buffer = 64;
    std::vector<std::vector<std::vector<LineVertex>>> polygons;
    // Two polygons with holes, one reaching past the tile's edges, one small.
    polygons.push_back(
        {star(rng, 1500, 1800, 1200, 1700, 40, true), star(rng, 1500, 1800, 200, 500, 12, false)});
    polygons.push_back({star(rng, 3300, 3300, 600, 820, 25, true)});
    polygons.push_back({star(rng, 600, 3600, 30, 90, 7, true)});
    for (size_t p = 0; p < polygons.size(); ++p) {
      t.feature_ids.push_back(p + 1);
      t.polygons.push_back(
          {uint32_t(p), 0, uint32_t(t.ring_sizes.size()), uint32_t(polygons[p].size())});
      for (const auto& r : polygons[p]) {
        t.ring_sizes.push_back(uint32_t(r.size()));
        t.vertices.insert(t.vertices.end(), r.begin(), r.end());
      }
    }
    const globe::viewer::DecodedAreaTile d = globe::viewer::area_tile_words(t);
    std::uniform_real_distribution<double> u(0, 4096);
    int checked = 0;
    for (int k = 0; k < 4000; ++k) {
      // Random points, and points on cell borders (multiples of 128) and corners.
      double x = u(rng), y = u(rng);
      if (k % 4 == 1) x = 128.0 * std::floor(x / 128);
      if (k % 4 == 2) x = 128.0 * std::floor(x / 128), y = 128.0 * std::floor(y / 128);
      x = std::min(x, 4096.0 - 1e-3), y = std::min(y, 4096.0 - 1e-3);
      for (uint32_t p = 0; p < polygons.size(); ++p) {
        // Points within a hair of an edge may fall either way: skip them.
        bool near = false;
        for (const auto& r : polygons[p])
          for (size_t i = 0; i < r.size(); ++i) {
            const LineVertex a = r[i], b = r[(i + 1) % r.size()];
            const double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
            const double s = std::clamp(((x - a.x) * dx + (y - a.y) * dy) / l2, 0.0, 1.0);
            near = near || std::hypot(a.x + s * dx - x, a.y + s * dy - y) < 1e-3;
          }
        if (near) continue;
        ++checked;
        EXPECT_EQ(globe::viewer::area_words_winding(d, p, x, y) != 0,
                  brute_inside(polygons[p], x, y))
            << "seed " << seed << " polygon " << p << " at " << x << ", " << y;
      }
    }
    EXPECT_GT(checked, 10000);
  }
}

TEST(AreaWords, AnEmptyTileHasEmptyCells) {
  const globe::viewer::DecodedAreaTile d = globe::viewer::area_tile_words(AreaTile{});
  EXPECT_EQ(d.entries, 0u);
  EXPECT_EQ(d.words.size(), size_t(d.grid) * d.grid + 1);
}

}  // namespace
