// Shard planning (kit/shard_plan): every subtree goes to exactly one shard,
// shards are contiguous runs of the Morton order with about equal work, the
// default split zoom gives 16 subtrees per shard, and bad specs are usage
// errors. Brute force in the test: the shares are recomputed from the plan
// of every shard.
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>

#include "kit/shard_plan.hpp"
#include "runtime/errors.hpp"

using globe::ShardPlan;
using globe::TileWork;
using tileformat::TileId;

namespace {

// Tiles of zoom 8 over a blob of the world, with uneven work.
std::vector<TileWork> uneven_tiles() {
  std::vector<TileWork> tiles;
  std::mt19937 rng(7);
  for (uint32_t y = 40; y < 160; ++y)
    for (uint32_t x = 10; x < 200; ++x)
      if ((x - 100) * (x - 100) + (y - 100) * (y - 100) < 60 * 60 || (x * 7 + y) % 13 == 0)
        tiles.push_back({TileId{8, x, y}, 1 + rng() % (x < 80 ? 40 : 3)});
  return tiles;
}

}  // namespace

TEST(ShardPlan, EverySubtreeInExactlyOneShardWithAboutEqualWork) {
  const auto tiles = uneven_tiles();
  for (int n : {1, 2, 3, 7, 64}) {
    std::map<TileId, int> owner;
    std::map<TileId, uint64_t> root_work;
    uint64_t total = 0, biggest_root = 0;
    std::vector<uint64_t> work(n);
    for (int i = 0; i < n; ++i) {
      const ShardPlan p = globe::plan_shard(tiles, 0, 4, {i, n});
      EXPECT_EQ(p.split_zoom, 4);
      for (const TileId& r : p.roots)
        EXPECT_TRUE(owner.emplace(r, i).second) << r.str() << " in two shards";
      work[i] = p.work;
      total = p.work_total;
    }
    for (const TileWork& t : tiles) {
      const TileId r{4, t.id.x >> 4, t.id.y >> 4};
      EXPECT_TRUE(owner.count(r)) << r.str() << " in no shard";
      root_work[r] += t.work;
    }
    for (const auto& [r, w] : root_work)
      biggest_root = std::max(biggest_root, w);
    uint64_t sum = 0;
    for (int i = 0; i < n; ++i) {
      sum += work[i];
      // A run ends within half a subtree of its share's end: off by at most
      // one subtree's work from an equal share.
      EXPECT_LE(work[i], total / n + biggest_root + 1) << "shard " << i << "/" << n;
    }
    EXPECT_EQ(sum, total);
  }
}

TEST(ShardPlan, ShardsAreContiguousRunsOfTheMortonOrder) {
  const auto tiles = uneven_tiles();
  // Morton key of a zoom-4 root (x in even bits), computed here bit by bit.
  auto key = [](const TileId& t) {
    uint64_t k = 0;
    for (int b = 0; b < 16; ++b)
      k |= (uint64_t((t.x >> b) & 1) << (2 * b)) | (uint64_t((t.y >> b) & 1) << (2 * b + 1));
    return k;
  };
  std::map<uint64_t, int> shard_by_key;
  for (int i = 0; i < 5; ++i)
    for (const TileId& r : globe::plan_shard(tiles, 0, 4, {i, 5}).roots)
      shard_by_key[key(r)] = i;
  int last = 0;
  for (const auto& [k, shard] : shard_by_key) {
    EXPECT_GE(shard, last) << "shard " << shard << " after " << last << " on the curve";
    last = shard;
  }
  EXPECT_EQ(last, 4);
}

TEST(ShardPlan, DefaultSplitZoomHasSixteenSubtreesPerShard) {
  const auto tiles = uneven_tiles();
  for (int n : {1, 4, 20}) {
    const ShardPlan p = globe::plan_shard(tiles, 0, std::nullopt, {0, n});
    EXPECT_GE(p.roots_total, 16u * n);
    const ShardPlan coarser = globe::plan_shard(tiles, 0, p.split_zoom - 1, {0, n});
    EXPECT_LT(coarser.roots_total, 16u * n) << "zoom " << p.split_zoom << " is not the coarsest";
  }
  // Never coarser than the build's coarsest zoom, never finer than its tiles.
  EXPECT_EQ(globe::plan_shard(tiles, 6, std::nullopt, {0, 2}).split_zoom, 6);
  EXPECT_EQ(globe::plan_shard(tiles, 0, std::nullopt, {0, 5000}).split_zoom, 8);
  EXPECT_THROW(globe::plan_shard(tiles, 0, 9, {0, 2}), globe::UsageError);
  EXPECT_THROW(globe::plan_shard(tiles, 5, 4, {0, 2}), globe::UsageError);
}

TEST(ShardPlan, ContainsTilesOfItsSubtreesOnly) {
  const ShardPlan p = globe::plan_shard(uneven_tiles(), 0, 4, {1, 3});
  ASSERT_FALSE(p.roots.empty());
  const TileId r = p.roots.front();
  EXPECT_TRUE(p.contains(r));
  EXPECT_TRUE(p.contains(TileId{8, r.x * 16 + 15, r.y * 16}));
  EXPECT_FALSE(p.contains(r.parent()));  // above the split zoom
  const ShardPlan other = globe::plan_shard(uneven_tiles(), 0, 4, {0, 3});
  EXPECT_FALSE(p.contains(other.roots.front()));
}

// Line builds share out the tiles above the split zoom too: each coarse tile
// goes to exactly one shard, which alone contains it, the work still sums
// to the total, and on the Morton curve a coarse tile stands just before
// the first subtree it covers (coarser first), in its shard's run.
TEST(ShardPlan, CoarseTilesGoToOneShardEachInMortonOrder) {
  const auto tiles = uneven_tiles();
  std::vector<TileWork> coarse;
  std::set<TileId> seen;
  for (const TileWork& t : tiles)
    for (int z = 1; z < 4; ++z) {
      const TileId c{z, t.id.x >> (8 - z), t.id.y >> (8 - z)};
      if (seen.insert(c).second) coarse.push_back({c, 50u * (4 - z)});
    }
  auto key = [](const TileId& t) {  // Morton key at zoom 4, bit by bit
    const TileId at4{4, t.x << (4 - t.z), t.y << (4 - t.z)};
    uint64_t k = 0;
    for (int b = 0; b < 16; ++b)
      k |= (uint64_t((at4.x >> b) & 1) << (2 * b)) | (uint64_t((at4.y >> b) & 1) << (2 * b + 1));
    return std::pair(k, t.z);
  };
  std::set<TileId> subtrees;
  for (const TileWork& t : tiles)
    subtrees.insert({4, t.id.x >> 4, t.id.y >> 4});
  for (int n : {1, 3, 8}) {
    std::vector<ShardPlan> plans;
    for (int i = 0; i < n; ++i)
      plans.push_back(globe::plan_shard(tiles, 0, 4, {i, n}, coarse));
    std::map<std::pair<uint64_t, int>, int> shard_by_key;
    uint64_t sum = 0;
    for (int i = 0; i < n; ++i) {
      for (const TileId& r : plans[i].roots)
        EXPECT_TRUE(shard_by_key.emplace(key(r), i).second) << r.str() << " in two shards";
      sum += plans[i].work;
    }
    EXPECT_EQ(sum, plans[0].work_total);
    EXPECT_EQ(plans[0].roots_total, subtrees.size() + coarse.size());
    EXPECT_EQ(shard_by_key.size(), subtrees.size() + coarse.size());
    int last = 0;
    for (const auto& [k, shard] : shard_by_key) {
      EXPECT_GE(shard, last) << "shard " << shard << " after " << last << " on the curve";
      last = shard;
    }
    for (const TileWork& c : coarse) {
      ASSERT_TRUE(shard_by_key.count(key(c.id))) << c.id.str() << " in no shard";
      const int owner = shard_by_key[key(c.id)];
      for (int i = 0; i < n; ++i)
        EXPECT_EQ(plans[i].contains(c.id), i == owner) << c.id.str();
    }
  }
}

TEST(ShardPlan, BadSpecsAreUsageErrors) {
  EXPECT_EQ(globe::parse_shard("3/8").index, 3);
  EXPECT_EQ(globe::parse_shard("3/8").count, 8);
  for (const char* bad : {"8/8", "-1/4", "1", "1/0", "a/b", "1/2/3", "1 /2", ""})
    EXPECT_THROW(globe::parse_shard(bad), globe::UsageError) << bad;
}
