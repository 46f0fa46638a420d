// Vector tiles on their way from a package to one GPU arena buffer, within a
// memory budget, for the passes that read their tiles per pixel (lines,
// areas). The pass reports which tiles its pixels asked for (GPU feedback)
// and which known tiles it used; the cache checks that a requested tile
// exists, decodes it on a loader thread into the words the shader reads
// (`Decoded::words`), places it in the arena (evicting the least recently used
// tiles that the last frame did not touch), and gives it a record. Tiles the
// package does not have get an empty record so the shader stops asking;
// corrupt ones (reported once on stderr) get a broken record, which the
// shader draws around (issue 55).
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "data/arena_allocator.hpp"
#include "data/block_cache.hpp"
#include "data/tile_loader.hpp"
#include "tileformat/package.hpp"
#include "tileformat/tiling.hpp"

namespace globe::viewer {

// One known tile as the shader sees it.
template <class Decoded>
struct ArenaRecord {
  tileformat::TileId id;
  bool empty = true;              // absent from the package or broken: nothing here
  bool broken = false;            // broken: its coarser or finer tiles are drawn instead
  uint64_t offset = 0, size = 0;  // arena range, in words
  Decoded tile;                   // words dropped after upload; counts kept
};

struct ArenaCacheStats {
  uint64_t budget_bytes = 0, resident_bytes = 0;
  size_t resident = 0, known_empty = 0;
  uint64_t loaded = 0, evictions = 0, broken = 0, bytes_read = 0;
};

// What a cache is of: its package's reader, tiling and zooms, and how its
// tiles are named in warnings ("line tile", "area tile") and what is drawn
// instead of a broken one.
struct ArenaCacheSource {
  std::string path;
  tileformat::TileReader* reader = nullptr;  // outlives the cache
  tileformat::Tiling tiling;
  int min_zoom = 0, max_zoom = 0;
  std::string tile_name;   // "line tile"
  std::string broken_use;  // "the lines of its coarser or finer tiles are drawn there"
  std::string budget_option = "--cache-mb";
};

template <class Decoded>
class ArenaTileCache {
 public:
  using Record = ArenaRecord<Decoded>;
  using Loader = TileLoader<Decoded>;

  ArenaTileCache(ArenaCacheSource source, uint64_t budget_bytes, typename Loader::Decode decode)
      : source_(std::move(source)), arena_(budget_bytes / 4) {
    stats_.budget_bytes = budget_bytes;
    loader_ = std::make_unique<Loader>(*source_.reader, std::move(decode));
  }
  virtual ~ArenaTileCache() = default;
  ArenaTileCache(const ArenaTileCache&) = delete;
  ArenaTileCache& operator=(const ArenaTileCache&) = delete;

  uint64_t arena_words() const { return arena_.capacity(); }
  void begin_frame() { ++frame_; }
  // GPU feedback of the frame just drawn.
  void mark_used(uint32_t record) {
    if (!live(record)) return;
    auto it = entries_.find(records_[record].id);
    if (it != entries_.end()) it->second.last_used = frame_;
  }
  // Returns whether the request was news: a tile now loading or now known
  // empty (false for tiles already known and for tiles past the tiling).
  bool request(tileformat::TileId id) {
    // Pixels past the tiling's edge ask for tiles no package can have.
    if (id.z < source_.min_zoom || id.z > source_.max_zoom || !source_.tiling.contains(id))
      return false;
    auto [it, fresh] = entries_.try_emplace(id);
    it->second.last_used = frame_;
    if (!fresh) return false;  // loading, resident or known empty
    if (!source_.reader->has_tile(id)) {
      it->second.record = static_cast<int>(new_record(id));
      return true;
    }
    it->second.loading = true;
    wanted_.push_back({id, -1});
    return true;
  }
  // Sends the new requests to the loader.
  void flush_requests() { loader_->submit_coarsest_first(wanted_); }
  // Places decoded tiles in the arena; returns the records to upload now
  // (with their words). The record table is rebuilt from records() each frame.
  std::vector<uint32_t> take_loaded() {
    std::vector<uint32_t> out;
    for (typename Loader::Done& d : loader_->take_done()) {
      const tileformat::TileId id = d.job.id;
      auto it = entries_.find(id);
      if (it == entries_.end()) continue;
      it->second.loading = false;
      stats_.bytes_read += d.bytes;
      if (d.absent) {  // as a tile has_tile() had known to be missing
        it->second.record = static_cast<int>(new_record(id));
        continue;
      }
      if (!d.ok) {
        std::fprintf(stderr, "globe-view: warning: %s: %s %s: %s; %s\n", source_.path.c_str(),
                     source_.tile_name.c_str(), id.str().c_str(), d.error.c_str(),
                     source_.broken_use.c_str());
        ++stats_.broken;
        const uint32_t r = new_record(id);
        records_[r].broken = true;
        it->second.record = static_cast<int>(r);
        continue;
      }
      const uint64_t size = std::max<size_t>(d.value.words.size(), 1);
      if (size > arena_.capacity()) {
        std::fprintf(stderr,
                     "globe-view: warning: %s: %s %s needs %.1f MB, more than its budget (raise "
                     "%s); it is not drawn\n",
                     source_.path.c_str(), source_.tile_name.c_str(), id.str().c_str(),
                     size * 4 / 1e6, source_.budget_option.c_str());
        ++stats_.broken;
        it->second.record = static_cast<int>(new_record(id));
        continue;
      }
      const auto offset = allocate_evicting(size);
      if (!offset) {
        entries_.erase(it);  // the budget is full of tiles in view; asked again later
        continue;
      }
      const uint32_t r = new_record(id);
      Record& rec = records_[r];
      rec.empty = false;
      rec.size = size;
      rec.offset = *offset;
      rec.tile = std::move(d.value);
      it->second.record = static_cast<int>(r);
      it->second.last_used = frame_;
      ++stats_.loaded;
      out.push_back(r);
    }
    // Forget known-empty tiles nobody looked at lately (they are asked again).
    size_t empties = 0;
    for (uint32_t r = 0; r < records_.size(); ++r)
      empties += live_[r] && records_[r].empty;
    if (empties > kMaxEmptyRecords)
      for (uint32_t r = 0; r < records_.size(); ++r)
        if (live_[r] && records_[r].empty && entries_.at(records_[r].id).last_used + 1 < frame_)
          free_record(r);
    return out;
  }
  void wait_for_loader() { loader_->wait_all(); }
  bool loader_busy() { return loader_->busy(); }

  // Records by index (index = GPU record); `live(i)` false for free slots.
  const std::vector<Record>& records() const { return records_; }
  bool live(uint32_t i) const { return i < live_.size() && live_[i]; }
  // Called after the words of a record are on the GPU.
  void drop_words(uint32_t record) { records_[record].tile.words = {}; }
  ArenaCacheStats stats() const {
    ArenaCacheStats s = stats_;
    s.resident_bytes = arena_.used() * 4;
    for (uint32_t r = 0; r < records_.size(); ++r)
      if (live_[r]) (records_[r].empty ? s.known_empty : s.resident)++;
    return s;
  }

 protected:
  // Forgets every tile (loaded or on its way): the next frames load them again.
  void forget_all() {
    wait_for_loader();
    loader_->take_done();
    for (uint32_t r = 0; r < records_.size(); ++r)
      if (live_[r]) free_record(r);
    entries_.clear();
    wanted_.clear();
  }
  // Stops the loader (a subclass whose decoder reads its members calls this
  // in its destructor).
  void stop_loader() { loader_.reset(); }

 private:
  static constexpr size_t kMaxEmptyRecords = 8192;
  struct Entry {
    bool loading = false;
    int record = -1;
    uint64_t last_used = 0;
  };
  uint32_t new_record(tileformat::TileId id) {
    uint32_t r;
    if (!free_records_.empty()) {
      r = free_records_.back();
      free_records_.pop_back();
    } else {
      r = static_cast<uint32_t>(records_.size());
      records_.emplace_back();
      live_.push_back(false);
    }
    records_[r] = Record{};
    records_[r].id = id;
    live_[r] = true;
    return r;
  }
  void free_record(uint32_t r) {
    const Record& rec = records_[r];
    if (!rec.empty) arena_.release(rec.offset, rec.size);
    entries_.erase(rec.id);
    live_[r] = false;
    free_records_.push_back(r);
  }
  // A range of `words` in the arena, evicting least recently used tiles the
  // last frame did not read; nullopt if those do not free enough.
  std::optional<uint64_t> allocate_evicting(uint64_t words) {
    for (;;) {
      if (auto at = arena_.allocate(words)) return at;
      int victim = -1;
      uint64_t victim_used = 0;
      for (uint32_t r = 0; r < records_.size(); ++r) {
        if (!live_[r] || records_[r].empty) continue;
        const uint64_t used = entries_.at(records_[r].id).last_used;
        if (used >= frame_) continue;
        if (victim < 0 || used < victim_used) victim = static_cast<int>(r), victim_used = used;
      }
      if (victim < 0) return std::nullopt;
      ++stats_.evictions;
      free_record(static_cast<uint32_t>(victim));
    }
  }

  ArenaCacheSource source_;
  ArenaAllocator arena_;
  uint64_t frame_ = 0;
  std::unordered_map<tileformat::TileId, Entry, TileKey> entries_;
  std::vector<Record> records_;
  std::vector<bool> live_;
  std::vector<uint32_t> free_records_;
  std::vector<typename Loader::Job> wanted_;
  ArenaCacheStats stats_;
  std::unique_ptr<Loader> loader_;  // last: stops before what it reads
};

}  // namespace globe::viewer
