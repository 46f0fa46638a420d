// External sort of tile records (what one feature contributes to one tile),
// so a build's memory does not grow with the input: records collect in
// memory up to a budget, are then sorted and spilled to a run file, and the
// runs are merged at the end. Records come back grouped by tile key, ordered
// by (key, seq, sub) - an order that never depends on thread count.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace globe {

struct TileRecord {
  uint64_t seq = 0;               // feature id
  uint32_t sub = 0;               // order within the feature
  uint32_t offset = 0, size = 0;  // payload bytes in TileGroup::bytes
};

// The records of one tile; payloads share one buffer.
struct TileGroup {
  uint64_t key = 0;
  std::vector<TileRecord> records;
  std::vector<uint8_t> bytes;
  std::span<const uint8_t> payload(const TileRecord& r) const {
    return {bytes.data() + r.offset, r.size};
  }
};

class TileSorter {
 public:
  // Run files (scratch_file.hpp) are named `scratch_prefix`.N and deleted by
  // the destructor.
  TileSorter(std::string scratch_prefix, size_t memory_budget_bytes);
  ~TileSorter();
  TileSorter(const TileSorter&) = delete;
  TileSorter& operator=(const TileSorter&) = delete;

  void add(uint64_t key, uint64_t seq, uint32_t sub, std::span<const uint8_t> payload);
  // Ends adding; then next_group() walks the tiles in key order.
  void finish();
  // The records of the next tile key; false when done.
  bool next_group(TileGroup& group);

  uint64_t records() const { return records_; }
  size_t spilled_runs() const { return runs_.size(); }
  uint64_t spilled_bytes() const { return spilled_bytes_; }

 private:
  struct Entry {
    uint64_t key, seq;
    uint32_t sub, len;
    size_t offset;
  };
  struct Run;
  void sort_memory();
  void spill();
  bool peek(uint64_t& key);  // smallest pending key
  std::string prefix_;
  size_t budget_;
  std::vector<uint8_t> arena_;
  std::vector<Entry> entries_;
  std::vector<std::unique_ptr<Run>> runs_;
  size_t mem_pos_ = 0;  // next in-memory entry while merging
  uint64_t records_ = 0, spilled_bytes_ = 0;
  bool finished_ = false;
};

}  // namespace globe
