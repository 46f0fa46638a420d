// Point tiles (docs/tileformat.md §11) on their way from a package to the
// chart pass, within a memory budget. The chart layer asks for the tiles its
// view selects (request); a loader thread reads and decodes them; decoded
// tiles stay resident (take_loaded) until the budget needs room, when the
// least recently used ones the last frame did not use go. Tiles the package
// does not have are known absent; corrupt ones are reported once on stderr
// and known as broken (the chart layer draws their children or parent:
// stand_in_tiles in render/point_tile_selection.hpp).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "data/block_cache.hpp"
#include "data/tile_loader.hpp"
#include "runtime/point_package.hpp"
#include "tileformat/point_tile.hpp"

namespace globe::viewer {

struct PointCacheStats {
  uint64_t budget_bytes = 0, resident_bytes = 0;
  size_t resident = 0, loading = 0;
  uint64_t loaded = 0, evictions = 0, broken = 0, bytes_read = 0;
};

class PointCache {
 public:
  PointCache(PointPackage package, uint64_t budget_bytes);
  ~PointCache();
  PointCache(const PointCache&) = delete;
  PointCache& operator=(const PointCache&) = delete;

  const PointPackage& package() const { return package_; }
  // Whether the package holds the tile (whatever its state here).
  bool exists(tileformat::TileId id);

  void begin_frame() { ++frame_; }
  // The resident tile (marked used by this frame), or nullptr: queues a load
  // unless the tile is absent, broken or loading.
  const tileformat::PointTile* get(tileformat::TileId id);
  // Whether the tile is on its way (queued or being decoded).
  bool loading(tileformat::TileId id) const;
  // Whether the tile could not be read (reported once on stderr).
  bool broken(tileformat::TileId id) const;
  // Sends this frame's loads to the loader thread.
  void flush_requests();
  // Makes the decoded tiles resident; returns how many.
  size_t take_loaded();
  bool loader_busy() { return loader_->busy(); }
  void wait_for_loader() { loader_->wait(); }
  PointCacheStats stats() const;

 private:
  using Loader = TileLoader<tileformat::PointTile>;
  enum class State { kLoading, kResident, kAbsent, kBroken };
  struct Entry {
    State state = State::kLoading;
    std::shared_ptr<const tileformat::PointTile> tile;
    uint64_t bytes = 0, last_used = 0;
  };
  void evict_for(uint64_t bytes);

  PointPackage package_;
  uint64_t frame_ = 0;
  std::unordered_map<tileformat::TileId, Entry, TileKey> entries_;
  std::unordered_map<tileformat::TileId, bool, TileKey> exists_;
  std::vector<Loader::Job> wanted_;
  PointCacheStats stats_;
  std::unique_ptr<Loader> loader_;  // last: stops before what it reads
};

}  // namespace globe::viewer
