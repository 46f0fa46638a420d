// The ground height under a point, read on the CPU from the terrain package
// itself (its own connection, independent of the GPU cache): the finest
// block there is, bilinear between its samples. Used to keep the camera
// above the ground.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "runtime/terrain_package.hpp"
#include "tileformat/mblock.hpp"
#include "tileformat/tile_id.hpp"

namespace globe::viewer {

class GroundProbe {
 public:
  // Opens `path` read-only a second time (throws InputError like the cache).
  explicit GroundProbe(const std::string& path);
  ~GroundProbe();

  // Height in metres of the ground at tiling-CRS point (x, y); nullopt off
  // the data (no block there, or a hole). Keeps the last blocks looked at,
  // so a camera moving within a tile costs no decoding.
  std::optional<double> height_at(double x, double y);

 private:
  // The decoded block `id` (nullptr: absent or broken), from recent_ or read.
  const tileformat::MBlock* block(tileformat::TileId id);

  static constexpr size_t kRecent = 8;
  TerrainPackage package_;
  std::vector<std::pair<tileformat::TileId, std::optional<tileformat::MBlock>>> recent_;
};

}  // namespace globe::viewer
