// Where a label goes (viewer/app/label_layout.hpp), on made-up screen paths:
// a line label's glyphs lie on the path, read left to right whichever way
// the path runs, and a copy whose glyphs would turn by more than the limit
// (a right angle) is not placed; a place's label sits right of its chart,
// with its other places left, above and below.
#include <gtest/gtest.h>

#include <cmath>

#include "app/label_layout.hpp"

namespace {

using namespace globe::viewer;

// Six glyphs 10 px apart at the atlas's size.
ShapedLabel six_glyphs() {
  ShapedLabel s;
  for (int i = 0; i < 6; ++i)
    s.glyphs.push_back({10.f * float(i), 0, 10, nullptr});
  s.width = 60, s.ascent = 18, s.descent = 6, s.ok = true;
  return s;
}

View flat_view() {
  View v;
  v.view = glm::dmat4(1), v.proj = glm::dmat4(1);
  v.eye = {0, 0, 10};
  v.width = 640, v.height = 360;
  return v;
}

std::vector<ScreenPathPoint> polyline(std::vector<std::pair<float, float>> pts) {
  std::vector<ScreenPathPoint> p;
  for (size_t i = 0; i < pts.size(); ++i) {
    const float s =
        i ? p.back().s + std::hypot(pts[i].first - p.back().x, pts[i].second - p.back().y) : 0.f;
    p.push_back({pts[i].first, pts[i].second, s, 100.f, uint32_t(i)});
  }
  return p;
}

std::vector<LabelLayout> along(const std::vector<ScreenPathPoint>& path, float ax, float ay) {
  const ShapedLabel s = six_glyphs();
  LabelText t{s};
  t.k = 1, t.size = 24, t.width = 60, t.ascent = 18, t.descent = 6;
  ProbeResult a{ax, ay, 100, true};
  const SightLines sight(flat_view());
  LabelSamples samples;
  std::vector<LabelLayout> out;
  lay_out_along_path(
      7, t, a, path, 3, 45, [](uint32_t) { return glm::dvec3(0, 0, 1); }, sight, samples, out);
  return out;
}

}  // namespace

TEST(LabelLayout, LineGlyphsLieOnThePathAndReadLeftToRight) {
  for (bool reversed : {false, true}) {
    auto pts = std::vector<std::pair<float, float>>{{100, 200}, {300, 150}, {500, 200}};
    if (reversed) std::reverse(pts.begin(), pts.end());
    const std::vector<LabelLayout> lays = along(polyline(pts), 300, 150);
    ASSERT_FALSE(lays.empty()) << reversed;
    for (const LabelLayout& l : lays) {
      ASSERT_EQ(l.pivots.size(), 6u);
      for (size_t g = 0; g < 6; ++g) {
        EXPECT_LE(std::abs(l.pivots[g][2]), std::numbers::pi / 2 + 1e-6) << "upside down";
        if (g) {
          EXPECT_GT(l.pivots[g][0], l.pivots[g - 1][0]) << "not left to right";
        }
        // On the path: the distance to the nearer of its two segments.
        const float x = l.pivots[g][0], y = l.pivots[g][1];
        auto seg = [&](float x0, float y0, float x1, float y1) {
          const float dx = x1 - x0, dy = y1 - y0;
          const float u =
              std::clamp(((x - x0) * dx + (y - y0) * dy) / (dx * dx + dy * dy), 0.f, 1.f);
          return std::hypot(x0 + u * dx - x, y0 + u * dy - y);
        };
        EXPECT_LT(std::min(seg(100, 200, 300, 150), seg(300, 150, 500, 200)), 0.01f);
      }
      EXPECT_EQ(l.sample_count, 6u);
      EXPECT_TRUE(l.along_line);
    }
  }
}

TEST(LabelLayout, NoCopyAcrossASharpTurn) {
  // A right angle at (300, 200): a copy centred on it would turn 90 degrees
  // between two glyphs; the copies elsewhere are straight.
  const std::vector<LabelLayout> lays = along(polyline({{0, 200}, {300, 200}, {300, 0}}), 300, 200);
  for (const LabelLayout& l : lays)
    for (size_t g = 1; g < l.pivots.size(); ++g)
      EXPECT_LE(std::abs(std::remainder(l.pivots[g][2] - l.pivots[g - 1][2], 2 * std::numbers::pi)),
                std::numbers::pi / 4 + 1e-6);
  // The copy on the corner (the middle one, key 7 << 4 | 3) is left out; the
  // one a spacing before it, on the straight leg, is placed.
  bool middle = false, before = false;
  for (const LabelLayout& l : lays) {
    middle = middle || (l.key & 15) == 3;
    before = before || (l.key & 15) == 2;
  }
  EXPECT_FALSE(middle);
  EXPECT_TRUE(before);
}

TEST(LabelLayout, APlaceLabelSitsBesideItsChartWithThreeOtherPlaces) {
  const ShapedLabel s = six_glyphs();
  LabelText t{s};
  t.k = 0.5f, t.size = 12, t.width = 30, t.ascent = 9, t.descent = 3;
  const SightLines sight(flat_view());
  LabelSamples samples;
  const ProbeResult a{200, 100, 50, true};
  const LabelLayout l = lay_out_at_anchor(3, t, a, false, 20, {0, 0, 1}, sight, samples);
  EXPECT_NEAR(l.box.x0, 200 + 23 - 1, 1e-4);  // clear of the 20 px chart
  EXPECT_NEAR((l.box.y0 + l.box.y1) / 2, 100 + (9 - 3) / 2.0 - 9 + 6, 1.5);
  ASSERT_EQ(l.shifts.size(), 4u);
  EXPECT_LT(l.box.x1 + l.shifts[1].dx, 200 - 20);  // left: clear of the chart too
  EXPECT_LT(l.box.y1 + l.shifts[2].dy, 100);       // above
  EXPECT_GT(l.box.y0 + l.shifts[3].dy, 100);       // below
  EXPECT_EQ(l.sample_count, 1u + 3u * 4u);         // the anchor, 3 pixels per place
  const LabelLayout area = lay_out_at_anchor(4, t, a, true, 0, {0, 0, 1}, sight, samples);
  EXPECT_NEAR((area.box.x0 + area.box.x1) / 2, 200, 1e-4);  // centred on its anchor
  EXPECT_EQ(area.shifts.size(), 1u);
}
