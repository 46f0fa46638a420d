// Comparing two packages as the scale-out contract states it
// (docs/scale-out.md): the same tiles, byte for byte, and the same metadata
// but the recorded command line and the file name. Used by the shard and
// cluster tests; the reference is always a one-machine build.
#pragma once

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "tileformat/package.hpp"

namespace globe_test {

// Every tile (same bytes) and metadata value (but globe:command_line and
// the file name) of `ours` equal `ref`'s.
inline void expect_same_package(const std::string& ours, const std::string& ref) {
  tileformat::PackageReader a(ours), b(ref);
  auto meta = [](tileformat::PackageReader& r) {
    auto m = r.metadata();
    m.erase("globe:command_line");
    m.erase("name");
    return m;
  };
  EXPECT_EQ(meta(a), meta(b));
  std::map<tileformat::TileId, std::vector<uint8_t>> tiles;
  b.for_each_tile([&](tileformat::TileId id, std::span<const uint8_t> blob) {
    tiles.emplace(id, std::vector<uint8_t>(blob.begin(), blob.end()));
  });
  size_t same = 0, differ = 0, extra = 0;
  a.for_each_tile([&](tileformat::TileId id, std::span<const uint8_t> blob) {
    auto it = tiles.find(id);
    if (it == tiles.end()) {
      ++extra;
      return;
    }
    if (std::equal(blob.begin(), blob.end(), it->second.begin(), it->second.end()))
      ++same;
    else if (differ++ < 5)
      ADD_FAILURE() << "tile " << id.str() << " differs";
    tiles.erase(it);
  });
  EXPECT_EQ(differ, 0u);
  EXPECT_EQ(extra, 0u) << "tiles the one-machine build does not have";
  EXPECT_EQ(tiles.size(), 0u) << "tiles missing, e.g. "
                              << (tiles.empty() ? "" : tiles.begin()->first.str());
  EXPECT_GT(same, 0u);
}

}  // namespace globe_test
