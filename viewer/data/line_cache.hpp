// Line-cluster tiles on their way from a package to the GPU, within a memory
// budget. The line pass reports which tiles its pixels asked for (GPU
// feedback) and which known tiles it used; the cache checks that a requested
// tile exists, decodes it on a loader thread into the words the shader reads
// (tile_words layout below), places it in the GPU arena (evicting the least
// recently used tiles that the last frame did not touch), and gives it a
// record. Tiles the package does not have get an empty record so the shader
// stops asking; their pixels show no lines. Corrupt ones (reported once on
// stderr) get a broken record: the shader draws the coarser tiles over them,
// or where there are none the finer tiles under them (issue 55).
//
// Tile words (all u32): cell offsets (C*C + 1, relative to the cell list),
// the cell list (segment indices), then 6 words per segment: ax, ay, bx, by
// (tile units as float bits), class id, distance along the run at a (units,
// float bits; for dashes). The segments are in the tile's run order, so a
// segment index names its run, and the run its feature.
//
// Highlighting (picking in the viewer): the runs of a chosen set of features
// take one more class, drawn over the others; changing the set reloads the
// resident tiles.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "data/arena_allocator.hpp"
#include "data/block_cache.hpp"
#include "data/tile_loader.hpp"
#include "runtime/line_package.hpp"
#include "tileformat/line_tile.hpp"

namespace globe::viewer {

inline constexpr uint32_t kLineWordsPerSegment = 6;

// What the loader makes of a blob.
struct DecodedLineTile {
  uint32_t extent = 0, grid = 0, reach = 0, segments = 0, cell_entries = 0;
  float longest = 0;  // the longest segment, in tile units
  std::vector<uint32_t> words;
};

// Features drawn in their own class instead of their runs' classes.
struct LineHighlight {
  std::vector<uint64_t> features;  // sorted feature ids
  uint32_t class_id = 0;
};

// Turns a decoded tile into its GPU words (exposed for tests); the runs of
// highlighted features get the highlight's class.
DecodedLineTile line_tile_words(const tileformat::LineTile& tile,
                                const LineHighlight* highlight = nullptr);

// The feature id of segment `segment` of the tile (in line_tile_words'
// order), or nullopt past its segments.
std::optional<uint64_t> segment_feature(const tileformat::LineTile& tile, uint32_t segment);

// One known tile as the shader sees it.
struct LineRecord {
  tileformat::TileId id;
  bool empty = true;              // absent from the package or broken: no lines here
  bool broken = false;            // broken: its coarser or finer tiles are drawn instead
  uint64_t offset = 0, size = 0;  // arena range, in words
  DecodedLineTile tile;           // words dropped after upload; counts kept
};

struct LineCacheStats {
  uint64_t budget_bytes = 0, resident_bytes = 0;
  size_t resident = 0, known_empty = 0;
  uint64_t loaded = 0, evictions = 0, broken = 0, bytes_read = 0;
};

class LineCache {
 public:
  LineCache(const std::string& path, LinePackage package, uint64_t budget_bytes);
  ~LineCache();
  LineCache(const LineCache&) = delete;
  LineCache& operator=(const LineCache&) = delete;

  const LinePackage& package() const { return package_; }
  uint64_t arena_words() const { return arena_.capacity(); }

  void begin_frame() { ++frame_; }
  // GPU feedback of the frame just drawn.
  void mark_used(uint32_t record);
  // Returns whether the request was news: a tile now loading or now known
  // empty (false for tiles already known and for tiles past the tiling).
  bool request(tileformat::TileId id);
  // Sends the new requests to the loader.
  void flush_requests();
  // Places decoded tiles in the arena; returns the records to upload now
  // (with their words). The record table is rebuilt from records() each frame.
  std::vector<uint32_t> take_loaded();
  void wait_for_loader() { loader_->wait_all(); }
  bool loader_busy() { return loader_->busy(); }

  // Records by index (index = GPU record); `live(i)` false for free slots.
  const std::vector<LineRecord>& records() const { return records_; }
  bool live(uint32_t i) const { return i < live_.size() && live_[i]; }
  // Called after the words of a record are on the GPU.
  void drop_words(uint32_t record) { records_[record].tile.words = {}; }
  LineCacheStats stats() const;
  // Draws these features in `highlight.class_id` from now on (none: empty
  // features): waits for the loader and forgets every tile, which the next
  // frames load again.
  void set_highlight(LineHighlight highlight);

 private:
  using Loader = TileLoader<DecodedLineTile>;
  struct Entry {
    bool loading = false;
    int record = -1;
    uint64_t last_used = 0;
  };
  uint32_t new_record(tileformat::TileId id);
  void free_record(uint32_t r);
  // A range of `words` in the arena, evicting least recently used tiles the
  // last frame did not read; nullopt if those do not free enough.
  std::optional<uint64_t> allocate_evicting(uint64_t words);

  std::string path_;
  LinePackage package_;
  ArenaAllocator arena_;
  uint64_t frame_ = 0;
  std::unordered_map<tileformat::TileId, Entry, TileKey> entries_;
  std::vector<LineRecord> records_;
  std::vector<bool> live_;
  std::vector<uint32_t> free_records_;
  std::vector<Loader::Job> wanted_;
  LineCacheStats stats_;
  std::mutex highlight_mutex_;  // the loader thread reads highlight_
  std::shared_ptr<const LineHighlight> highlight_;
  std::unique_ptr<Loader> loader_;  // last: stops before what it reads
};

}  // namespace globe::viewer
