// The whole-grid depression fill (depression_fill.hpp: filled_surface, Zhou
// et al.'s variant) against a brute force written here: the filled height
// of a cell is the least, over paths to a cell next to no data, of the
// highest raw height on the path, found by relaxing
// W = max(z, least W of the neighbours) until nothing changes.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "analysis/flow/chunk_heights.hpp"
#include "analysis/flow/depression_fill.hpp"

namespace {

using namespace globe::flow;

std::vector<int32_t> brute_force_fill(const Chunk& c, const std::vector<int32_t>& z) {
  const ChunkWindow win(c);
  const int s = win.stride();
  std::vector<int64_t> w(z.size(), INT64_MAX);
  for (size_t k = 0; k < z.size(); ++k)
    if (z[k] != kNoData && at_data_edge(z, k, s)) w[k] = z[k];
  for (bool changed = true; changed;) {
    changed = false;
    for (int y = 0; y < c.h; ++y)
      for (int x = 0; x < c.w; ++x) {
        const size_t k = win.at(x, y);
        if (z[k] == kNoData) continue;
        int64_t least = w[k];
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const size_t n = win.at(x + dx, y + dy);
            if (z[n] != kNoData) least = std::min(least, std::max<int64_t>(z[k], w[n]));
          }
        if (least < w[k]) w[k] = least, changed = true;
      }
  }
  std::vector<int32_t> out(z.size(), kNoData);
  for (size_t k = 0; k < z.size(); ++k)
    if (z[k] != kNoData) out[k] = int32_t(w[k]);
  return out;
}

TEST(FilledSurface, EqualsTheLeastHighestPathToTheDataEdge) {
  for (uint32_t seed = 1; seed <= 20; ++seed) {
    std::mt19937 rng(seed);
    Chunk c;
    c.w = 20 + int(rng() % 60), c.h = 20 + int(rng() % 60);
    const ChunkWindow win(c);
    std::vector<int32_t> z(win.size(), kNoData);  // the ring: no data
    // Few heights (many equal, wide flats), pits, and holes of no data.
    const int levels = seed % 2 ? 8 : 1000;
    for (int y = 0; y < c.h; ++y)
      for (int x = 0; x < c.w; ++x)
        z[win.at(x, y)] = rng() % 40 == 0 ? kNoData : int32_t(rng() % levels) - levels / 2;
    const std::vector<int32_t> filled = filled_surface(c, z);
    EXPECT_EQ(filled, brute_force_fill(c, z)) << "seed " << seed;
    EXPECT_EQ(filled, fill_chunk(c, z).filled) << "seed " << seed;
  }
}

}  // namespace
