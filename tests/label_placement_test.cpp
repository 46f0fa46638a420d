// Label placement (viewer/app/label_placement.hpp), on bids made up here: no
// two labels shown overlap (checked against every pair, not the grid); the
// higher priority wins; a label shown keeps its place against a newcomer of
// higher priority; a label appears only after fitting twice (a one-frame
// chance never shows it) with room around it, fades in, and goes at once
// when it may not be drawn; the placement budget defers the rest without
// losing them.
#include <gtest/gtest.h>

#include <random>

#include "app/label_placement.hpp"

namespace {

using globe::viewer::LabelBid;
using globe::viewer::LabelPlacementOptions;
using globe::viewer::LabelPlacer;
using globe::viewer::ScreenBox;

LabelBid bid(uint64_t key, double priority, float x, float y, float w = 60, float h = 14) {
  LabelBid b;
  b.key = key;
  b.priority = priority;
  b.boxes = {ScreenBox{x, y, x + w, y + h}};
  b.drawable = true;
  return b;
}

std::vector<float> alphas(const std::vector<globe::viewer::LabelPlace>& places) {
  std::vector<float> a;
  for (const auto& p : places)
    a.push_back(p.alpha);
  return a;
}

bool overlap(const LabelBid& a, const LabelBid& b) {
  for (const ScreenBox& p : a.boxes)
    for (const ScreenBox& q : b.boxes)
      if (p.x0 < q.x1 && q.x0 < p.x1 && p.y0 < q.y1 && q.y0 < p.y1) return true;
  return false;
}

}  // namespace

TEST(LabelPlacement, NoTwoShownOverlapAndPriorityDecides) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> x(-80, 700), y(-80, 420), w(10, 200), p(0, 1);
  LabelPlacer placer(LabelPlacementOptions{640, 360});
  std::vector<LabelBid> bids;
  for (uint64_t k = 0; k < 2000; ++k) {
    LabelBid b = bid(k, p(rng), x(rng), y(rng), w(rng), 12);
    if (k % 7 == 0) {  // a line label: a chain of glyph boxes
      b.boxes.clear();
      const float x0 = x(rng), y0 = y(rng);
      for (int g = 0; g < 8; ++g)
        b.boxes.push_back({x0 + 9.f * g, y0 + 3.f * g, x0 + 9.f * g + 10, y0 + 3.f * g + 10});
    }
    bids.push_back(b);
  }
  const std::vector<float> alpha = alphas(placer.place(bids, 0, true));
  size_t shown = 0;
  for (size_t i = 0; i < bids.size(); ++i) {
    if (alpha[i] <= 0) continue;
    ++shown;
    EXPECT_EQ(alpha[i], 1.f);  // a still picture: full opacity at once
    for (size_t j = 0; j < i; ++j)
      EXPECT_FALSE(alpha[j] > 0 && overlap(bids[i], bids[j])) << i << " overlaps " << j;
  }
  EXPECT_GT(shown, 50u);
  // Every label hidden overlaps a shown one of higher priority.
  for (size_t i = 0; i < bids.size(); ++i) {
    if (alpha[i] > 0) continue;
    bool blocked = false;
    for (size_t j = 0; j < bids.size() && !blocked; ++j)
      blocked = alpha[j] > 0 && bids[j].priority >= bids[i].priority && overlap(bids[i], bids[j]);
    EXPECT_TRUE(blocked) << "label " << i << " was room to spare";
  }
}

TEST(LabelPlacement, AShownLabelKeepsItsPlaceAgainstAHigherNewcomer) {
  LabelPlacer placer(LabelPlacementOptions{640, 360});
  std::vector<LabelBid> bids = {bid(1, 0.2, 100, 100)};
  EXPECT_EQ(alphas(placer.place(bids, 0, true))[0], 1.f);
  bids.push_back(bid(2, 0.9, 110, 104));  // overlaps, higher priority
  for (int f = 0; f < 10; ++f) {
    const std::vector<float> a = alphas(placer.place(bids, 1.0 / 30, false));
    EXPECT_GT(a[0], 0.f) << "frame " << f;
    EXPECT_EQ(a[1], 0.f) << "frame " << f;
  }
}

TEST(LabelPlacement, AppearsAfterTwoFramesFadesInAndGoesAtOnce) {
  LabelPlacer placer(LabelPlacementOptions{640, 360});
  std::vector<LabelBid> bids = {bid(5, 1, 10, 10)};
  EXPECT_EQ(alphas(placer.place(bids, 1.0 / 30, false))[0], 0.f);  // fitted once: not yet
  const float a1 = alphas(placer.place(bids, 1.0 / 30, false))[0];
  EXPECT_GT(a1, 0.f);
  EXPECT_LT(a1, 1.f);  // fading in
  float a = a1;
  for (int f = 0; f < 10; ++f) {
    const float next = alphas(placer.place(bids, 1.0 / 30, false))[0];
    EXPECT_GE(next, a);
    a = next;
  }
  EXPECT_EQ(a, 1.f);
  bids[0].drawable = false;  // behind terrain: gone in the same frame
  EXPECT_EQ(alphas(placer.place(bids, 1.0 / 30, false))[0], 0.f);
}

TEST(LabelPlacement, AOneFrameChanceNeverShowsALabel) {
  LabelPlacer placer(LabelPlacementOptions{640, 360});
  // Label 2 is blocked by label 1 except in every other frame: it never
  // fits twice in a row, so it never blinks on.
  for (int f = 0; f < 20; ++f) {
    std::vector<LabelBid> bids = {bid(2, 0.1, 100, 100)};
    if (f % 2 == 0) bids.push_back(bid(1, 0.9, 100, 100));
    const std::vector<float> a = alphas(placer.place(bids, 1.0 / 30, false));
    EXPECT_EQ(a[0], 0.f) << "frame " << f;
  }
}

TEST(LabelPlacement, TooSmallFadesOutKeepingItsRoom) {
  LabelPlacer placer(LabelPlacementOptions{640, 360});
  std::vector<LabelBid> bids = {bid(1, 0.5, 100, 100)};
  alphas(placer.place(bids, 0, true));
  bids[0].legible = false;
  bids.push_back(bid(2, 0.9, 100, 100));
  const std::vector<float> a = alphas(placer.place(bids, 1.0 / 30, false));
  EXPECT_GT(a[0], 0.f);
  EXPECT_LT(a[0], 1.f);
  EXPECT_EQ(a[1], 0.f);  // not over the one fading out
}

TEST(LabelPlacement, TheBudgetDefersWithoutLosing) {
  LabelPlacer placer(LabelPlacementOptions{640, 360});
  std::vector<LabelBid> bids;
  for (uint64_t k = 0; k < 30; ++k)
    bids.push_back(bid(k, double(k), 40.f * float(k % 15), 40.f * float(k / 15), 18, 12));
  size_t shown = 0;
  for (int f = 0; f < 12; ++f) {
    const std::vector<float> a = alphas(placer.place(bids, 1.0 / 30, false, 5));
    EXPECT_LE(placer.tried() - shown, 5u + 0u);
    shown = 0;
    for (float v : a)
      shown += v > 0;
  }
  EXPECT_EQ(shown, 30u);
}

TEST(LabelPlacement, TakesTheNextPlaceAndKeepsIt) {
  LabelPlacer placer(LabelPlacementOptions{640, 360});
  LabelBid a = bid(1, 0.1, 100, 100);
  a.shifts = {{0, 0}, {-80, 0}, {0, -20}};
  // The right is taken by a chart: the label goes left.
  const std::vector<ScreenBox> chart = {{95, 95, 170, 120}};
  auto p = placer.place({a}, 0, true, -1, chart);
  EXPECT_EQ(p[0].alpha, 1.f);
  EXPECT_EQ(p[0].shift, 1);
  // The chart goes: the label stays left (no jump back while shown).
  p = placer.place({a}, 1.0 / 30, false);
  EXPECT_EQ(p[0].shift, 1);
  // Terrain hides the left place: it moves to one still clear.
  a.clear = {1, 0, 1};
  p = placer.place({a}, 1.0 / 30, false);
  EXPECT_GT(p[0].alpha, 0.f);
  EXPECT_EQ(p[0].shift, 0);
}

TEST(LabelPlacement, NothingCoversAnObstacle) {
  LabelPlacer placer(LabelPlacementOptions{640, 360});
  const auto p = placer.place({bid(1, 1, 100, 100)}, 0, true, -1, {{150, 90, 160, 200}});
  EXPECT_EQ(p[0].alpha, 0.f);
}

TEST(LabelPlacement, ANewLabelNeedsRoomAroundItWhileTheCameraMoves) {
  LabelPlacer placer(LabelPlacementOptions{640, 360});
  std::vector<LabelBid> bids = {bid(1, 0.9, 100, 100), bid(2, 0.1, 162, 100)};  // 2 px apart
  for (int f = 0; f < 5; ++f)
    EXPECT_EQ(alphas(placer.place(bids, 1.0 / 30, false))[1], 0.f) << "frame " << f;
  // A still picture places them tight.
  LabelPlacer still(LabelPlacementOptions{640, 360});
  EXPECT_EQ(alphas(still.place(bids, 0, true))[1], 1.f);
}
