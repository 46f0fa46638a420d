// Terrain blocks on their way from a package to the GPU, within a memory
// budget. The render thread asks for blocks (request); a loader thread reads
// and decodes them; the render thread takes the decoded ones (take_loaded),
// uploads them into the texture slot reserved at request time, and from then
// on the block is resident with its error tree and height range on the CPU.
// A frame never waits: callers draw coarser until a block is resident.
//
// Budget: every slot costs one block's GPU texels (heights + mask) plus its
// CPU error tree; a request is only made when a slot is free or can be freed
// by evicting a block that the current frame did not use (LRU), so the
// budget holds however far the camera flies.
//
// A tile that cannot be read is drawn from a stand-in made of its children's
// or its parent's samples (block_substitute.hpp), reported once on stderr;
// one with neither stays broken (a hole of its footprint). Its analysis
// likewise.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "data/analysis_texels.hpp"
#include "data/tile_loader.hpp"
#include "runtime/terrain_package.hpp"
#include "tileformat/tile_id.hpp"

namespace globe::viewer {

struct TileKey {
  size_t operator()(const tileformat::TileId& t) const {
    return (size_t(t.z) * 0x9E3779B97F4A7C15ULL) ^ (size_t(t.x) * 0xC2B2AE3D27D4EB4FULL) ^
           (size_t(t.y) * 0x165667B19E3779F9ULL);
  }
};

enum class BlockState { kAbsent, kNotLoaded, kLoading, kResident, kBroken };

struct ResidentBlock {
  int slot = -1;
  float min_h = 0, max_h = 0;          // metres, over all samples (holes are filled)
  std::vector<uint32_t> vertex_error;  // quanta, per split vertex (tileformat §6)
  uint64_t last_used_frame = 0;
  // A stand-in for a broken tile made from its children (block_substitute.hpp):
  // its errors are unknown, so the selection splits through it to them.
  bool split_through = false;
};

// A decoded block waiting for upload into `slot`.
struct LoadedBlock {
  tileformat::TileId id;
  int slot = -1;
  std::vector<float> heights;   // size*size, metres, row-major from the north row
  std::vector<uint8_t> mask;    // size*size, 255 = data, 0 = hole
  std::vector<float> analysis;  // size*size*4 (analysis_texels.hpp) with an analysis package
  std::vector<float> flow;      // size*size*kFlowTexel (flow_texels) with an analysis package
};

// An analysis package drawn with the terrain (the same tiles); its reader is
// used by the loader thread only.
struct AnalysisSource {
  std::string path;
  std::unique_ptr<tileformat::TileReader> reader;
};

// What the loader thread makes of one blob.
struct DecodedBlock {
  LoadedBlock block;
  ResidentBlock meta;
  // Why the block is a stand-in (block_substitute.hpp), and why its analysis
  // is; empty when read as it is.
  std::string warning, analysis_warning;
};

struct CacheStats {
  uint64_t bytes_read = 0;  // blob bytes read from the package
  uint64_t blocks_loaded = 0, evictions = 0, broken = 0;
  size_t resident = 0, slots = 0;
  uint64_t budget_bytes = 0, resident_bytes = 0;
};

class BlockCache {
 public:
  // budget_bytes: memory for resident blocks; at least 8 blocks are allowed.
  // With `analysis`, each block also carries its analysis texels.
  BlockCache(const std::string& path, TerrainPackage package, uint64_t budget_bytes,
             std::optional<AnalysisSource> analysis = std::nullopt);
  const TerrainPackage& package() const { return package_; }
  ~BlockCache();
  BlockCache(const BlockCache&) = delete;
  BlockCache& operator=(const BlockCache&) = delete;

  size_t slot_count() const { return slots_; }
  uint64_t bytes_per_slot() const { return bytes_per_slot_; }

  // Frame bookkeeping: blocks touched by the current frame are never evicted.
  void begin_frame() { ++frame_; }
  uint64_t frame() const { return frame_; }

  BlockState state(tileformat::TileId id);
  // Marks the block used by this frame; nullptr unless resident.
  const ResidentBlock* use(tileformat::TileId id);
  // Queues a load (lower priority value = sooner). No-op unless kNotLoaded
  // or if no slot can be had this frame.
  void request(tileformat::TileId id, double priority);
  // Sends this frame's requests to the loader, most urgent first.
  void flush_requests();
  // Decoded blocks to upload now (they are resident from this call on).
  std::vector<LoadedBlock> take_loaded();
  // Blocks until the loader has finished something or has nothing to do.
  void wait_for_loader() { loader_->wait(); }
  bool loader_busy() { return loader_->busy(); }
  CacheStats stats() const;
  // Every resident block and its texture slot (for height lookups on the GPU).
  std::vector<std::pair<tileformat::TileId, int>> resident_slots() const;

 private:
  struct Entry {
    BlockState state = BlockState::kNotLoaded;
    ResidentBlock block;
  };
  using Loader = TileLoader<DecodedBlock>;
  int take_slot();

  std::string path_;
  TerrainPackage package_;
  size_t slots_ = 0;
  uint64_t bytes_per_slot_ = 0;
  uint64_t frame_ = 0;
  std::unordered_map<tileformat::TileId, Entry, TileKey> entries_;
  std::vector<int> free_slots_;
  std::vector<std::pair<double, tileformat::TileId>> wanted_;
  CacheStats stats_;
  std::set<std::pair<tileformat::TileId, bool>> warned_;  // (tile, terrain or analysis)
  std::optional<AnalysisSource> analysis_;
  std::unique_ptr<Loader> loader_;  // last: stops before what it reads
};

}  // namespace globe::viewer
