// Heights of a terrain package at any point of its tiling's CRS, for the web
// exports and the server (docs/web.md): bilinear between the samples of one
// block. A block's samples sit on its tile's edges (tileformat §5), so the
// four around a point always lie in one block and neighbouring blocks agree
// on their shared edge. The block of the zoom asked for is used, else the
// nearest coarser one the package has.
//
// TerrainBlocks decodes a package's blocks on demand and keeps them up to a
// byte budget, shared by all threads (the package's reader takes one tile()
// at a time); a TerrainSampler is one thread's cheap view of them.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "runtime/terrain_package.hpp"
#include "tileformat/mblock.hpp"
#include "tileformat/tile_id.hpp"
#include "web/lru_cache.hpp"

namespace globe::web {

uint64_t tile_key(tileformat::TileId id);

class TerrainBlocks {
 public:
  TerrainBlocks(TerrainPackage& package, size_t max_bytes);
  // The decoded block of a tile; nullptr where the package has none. Throws
  // InputError naming the package and tile for a block that does not decode.
  std::shared_ptr<const tileformat::MBlock> block(tileformat::TileId id);
  TerrainPackage& package() { return package_; }

 private:
  TerrainPackage& package_;
  std::mutex read_mutex_;
  LruCache<uint64_t, tileformat::MBlock> cache_;
};

class TerrainSampler {
 public:
  explicit TerrainSampler(TerrainBlocks& blocks) : blocks_(blocks) {}

  // Metres at the points (xs[k], ys[j]) of a grid in the tiling's CRS,
  // row-major into `out` (xs.size() * ys.size()), from blocks of `zoom` or
  // coarser (clamped to the package's zooms); NaN where no block covers a
  // point. Columns and rows are placed in the tiles once, not per point.
  void heights(const std::vector<double>& xs, const std::vector<double>& ys, int zoom,
               std::vector<double>& out);
  // The decoded block of a tile (nullptr where none), held here until
  // `kRecent` other blocks have been asked for.
  const tileformat::MBlock* block(tileformat::TileId id);

 private:
  static constexpr int kRecent = 4;
  TerrainBlocks& blocks_;
  struct Recent {
    uint64_t key = ~uint64_t{0};
    std::shared_ptr<const tileformat::MBlock> block;
  };
  std::array<Recent, kRecent> recent_;  // most recent first
};

}  // namespace globe::web
