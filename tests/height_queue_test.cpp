// The flow solver's stable height queue (height_queue.hpp) against a brute
// force written here: the queued (height, order of queueing) pairs, the
// least taken each time.
#include <gtest/gtest.h>

#include <random>
#include <set>
#include <utility>

#include "analysis/flow/height_queue.hpp"

namespace {

using globe::flow::HeightQueue;

// Random pushes and pops of heights in lowest .. highest, `strays` of them
// outside that range, against an ordered set of (height, arrival).
void check_against_brute_force(HeightQueue& q, int32_t lowest, int32_t highest, size_t cells,
                               int strays, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int32_t> height(lowest, highest);
  std::set<std::pair<int32_t, uint32_t>> brute;
  std::vector<int32_t> height_of;
  q.reset(lowest, highest, cells);
  for (int step = 0; step < 20000; ++step) {
    if (brute.empty() || rng() % 3 != 0) {
      int32_t h = height(rng);
      if (strays > 0 && rng() % 500 == 0) {
        h = rng() % 2 ? lowest - 1 - int32_t(rng() % 1000) : highest + 1 + int32_t(rng() % 1000);
        --strays;
      }
      const uint32_t cell = uint32_t(height_of.size());
      height_of.push_back(h);
      q.push(h, cell);
      brute.insert({h, cell});  // cells are numbered in order of arrival
    } else {
      ASSERT_FALSE(q.empty());
      const uint32_t cell = q.pop();
      ASSERT_EQ(cell, brute.begin()->second) << "step " << step;
      brute.erase(brute.begin());
    }
  }
  while (!brute.empty()) {
    ASSERT_EQ(q.pop(), brute.begin()->second);
    brute.erase(brute.begin());
  }
  EXPECT_TRUE(q.empty());
}

TEST(HeightQueue, TakesTheLowestThenTheEarliest) {
  HeightQueue q;                                           // reused: buffers kept between searches
  check_against_brute_force(q, 100, 140, 1000, 0, 1);      // few heights: many equal
  check_against_brute_force(q, -5000, 60000, 1000, 0, 2);  // buckets, four levels of bits
  check_against_brute_force(q, 100, 140, 1000, 0, 3);      // smaller again after larger
  check_against_brute_force(q, -2000000000, 2000000000, 1000, 0, 4);  // the heap
}

TEST(HeightQueue, CellsOutsideTheGivenRangeKeepTheOrder) {
  HeightQueue q;
  check_against_brute_force(q, 0, 300, 1000, 20, 5);
  check_against_brute_force(q, 0, 300, 1000, 0, 6);  // buckets again after the switch
}

}  // namespace
