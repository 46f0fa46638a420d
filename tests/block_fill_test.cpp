// Hole filling: valid samples untouched, every hole filled, and a shared edge
// filled identically by two blocks that see the same edge samples.
#include <gtest/gtest.h>

#include <random>

#include "runtime/block_fill.hpp"

namespace {
constexpr int kSize = 33;
}

TEST(BlockFill, KeepsDataAndFillsEveryHole) {
  std::vector<int32_t> q(kSize * kSize, 0);
  std::vector<uint8_t> valid(q.size(), 0);
  for (int y = 10; y < 20; ++y)
    for (int x = 5; x < 15; ++x) {
      q[y * kSize + x] = 500 + x;
      valid[y * kSize + x] = 1;
    }
  auto filled = q;
  globe::fill_holes(filled, valid, kSize, -7);
  for (size_t i = 0; i < q.size(); ++i) {
    if (valid[i]) {
      EXPECT_EQ(filled[i], q[i]);
    }
  }
  // Corners without data take the fill height; the interior stays within the data range.
  EXPECT_EQ(filled[0], -7);
  EXPECT_EQ(filled[kSize * kSize - 1], -7);
  for (int y = 1; y < kSize - 1; ++y)
    for (int x = 1; x < kSize - 1; ++x) {
      EXPECT_GE(filled[y * kSize + x], -7);
      EXPECT_LE(filled[y * kSize + x], 514);
    }
}

TEST(BlockFill, SharedEdgeIsFilledIdenticallyFromBothSides) {
  std::mt19937 rng(42);
  for (int trial = 0; trial < 20; ++trial) {
    // Block A's east edge is block B's west edge; interiors differ randomly.
    std::vector<int32_t> qa(kSize * kSize), qb(kSize * kSize);
    std::vector<uint8_t> va(qa.size()), vb(qb.size());
    for (size_t i = 0; i < qa.size(); ++i) {
      qa[i] = static_cast<int32_t>(rng() % 1000);
      qb[i] = static_cast<int32_t>(rng() % 1000);
      va[i] = rng() % 3 == 0;
      vb[i] = rng() % 3 == 0;
    }
    for (int y = 0; y < kSize; ++y) {
      qb[y * kSize] = qa[y * kSize + kSize - 1];
      vb[y * kSize] = va[y * kSize + kSize - 1];
    }
    globe::fill_holes(qa, va, kSize, 3);
    globe::fill_holes(qb, vb, kSize, 3);
    for (int y = 0; y < kSize; ++y)
      ASSERT_EQ(qa[y * kSize + kSize - 1], qb[y * kSize]) << "row " << y;
  }
}
