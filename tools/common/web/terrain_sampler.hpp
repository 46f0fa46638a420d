// Heights of a terrain package at any point of its tiling's CRS, for the web
// exports and the server (docs/web.md): bilinear between the samples of one
// block. A block's samples sit on its tile's edges (tileformat §5), so the
// four around a point always lie in one block and neighbouring blocks agree
// on their shared edge. The block of the zoom asked for is used, else the
// nearest coarser one the package has. Blocks are decoded on demand and kept,
// at most `max_blocks` (least recently used dropped). One sampler per thread,
// all sharing `read_mutex`: the package's reader takes one tile() at a time.
#pragma once

#include <cstdint>
#include <list>
#include <memory>
#include <mutex>
#include <optional>
#include <unordered_map>

#include "terrain_package.hpp"
#include "tileformat/mblock.hpp"

namespace globe::web {

class TerrainSampler {
 public:
  TerrainSampler(TerrainPackage& package, std::mutex& read_mutex, size_t max_blocks = 64);

  // Metres at (crs_x, crs_y) from blocks of `zoom` or coarser (clamped to the
  // package's zooms); nullopt where no block covers the point. Throws
  // InputError naming the package and tile for a block that does not decode.
  std::optional<double> height(double crs_x, double crs_y, int zoom);
  // The decoded block of a tile; nullptr where the package has none. Valid
  // until the next call (it may be dropped from the cache).
  const tileformat::MBlock* block(tileformat::TileId id);

 private:
  TerrainPackage& package_;
  std::mutex& read_mutex_;
  size_t max_blocks_;
  struct Cached {
    std::unique_ptr<tileformat::MBlock> block;  // nullptr: the package has no tile there
    std::list<uint64_t>::iterator age;
  };
  std::unordered_map<uint64_t, Cached> cache_;
  std::list<uint64_t> ages_;  // most recent first
};

}  // namespace globe::web
