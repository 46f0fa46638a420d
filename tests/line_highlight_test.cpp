// Picking and highlighting in the viewer's line tiles (viewer/data/line_cache):
// a segment index of the GPU words names the feature the library's own
// segment list gives it, and highlighted features, and only they, take the
// highlight class.
#include <gtest/gtest.h>

#include "data/line_cache.hpp"

namespace {

using globe::viewer::kLineWordsPerSegment;
using globe::viewer::LineHighlight;

// Three features: a 3-segment run, a 1-segment run, a 2-segment run and one
// more 1-segment run of the first feature.
tileformat::LineTile three_features() {
  tileformat::LineTile t;
  t.extent = 64, t.grid = 1, t.reach = 1;
  t.feature_ids = {7, 12, 40};
  auto run = [&](uint32_t feature, uint32_t cls, int n) {
    t.runs.push_back({feature, cls, uint32_t(t.vertices.size()), uint32_t(n)});
    for (int i = 0; i < n; ++i)
      t.vertices.push_back({int32_t(i), int32_t(t.runs.size())});
  };
  run(0, 1, 4);
  run(1, 2, 2);
  run(2, 0, 3);
  run(0, 1, 2);
  t.cell_offsets = {0, t.segment_count()};
  for (uint32_t s = 0; s < t.segment_count(); ++s)
    t.cell_segments.push_back(s);
  return t;
}

TEST(LineHighlight, SegmentsNameTheFeatureOfTheirRun) {
  const tileformat::LineTile t = three_features();
  const std::vector<tileformat::LineSegment> segs = t.segments();
  ASSERT_EQ(segs.size(), 7u);
  for (uint32_t s = 0; s < segs.size(); ++s)
    EXPECT_EQ(globe::viewer::segment_feature(t, s), t.feature_ids[segs[s].feature]) << s;
  EXPECT_FALSE(globe::viewer::segment_feature(t, 7).has_value());
}

TEST(LineHighlight, OnlyHighlightedFeaturesTakeTheHighlightClass) {
  const tileformat::LineTile t = three_features();
  const std::vector<tileformat::LineSegment> segs = t.segments();
  const size_t base = t.cell_offsets.size() + t.cell_segments.size();
  auto classes = [&](const LineHighlight* h) {
    const auto d = globe::viewer::line_tile_words(t, h);
    std::vector<uint32_t> c;
    for (size_t s = 0; s < segs.size(); ++s)
      c.push_back(d.words[base + s * kLineWordsPerSegment + 4]);
    return c;
  };
  EXPECT_EQ(classes(nullptr), (std::vector<uint32_t>{1, 1, 1, 2, 0, 0, 1}));
  const LineHighlight h{{7, 40, 99}, 3};
  EXPECT_EQ(classes(&h), (std::vector<uint32_t>{3, 3, 3, 2, 3, 3, 3}));
  const LineHighlight one{{12}, 5};
  EXPECT_EQ(classes(&one), (std::vector<uint32_t>{1, 1, 1, 5, 0, 0, 1}));
}

}  // namespace
