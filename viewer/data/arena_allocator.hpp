// First-fit allocation of ranges in a fixed-size arena (the line tiles' GPU
// buffer, in 32-bit words). Freed ranges merge with their neighbours.
#pragma once

#include <cstdint>
#include <map>
#include <optional>

namespace globe::viewer {

class ArenaAllocator {
 public:
  explicit ArenaAllocator(uint64_t capacity) : capacity_(capacity) {
    if (capacity) free_[0] = capacity;
  }
  uint64_t capacity() const { return capacity_; }
  uint64_t used() const { return used_; }

  // Offset of a free range of `size` (> 0), or nullopt if none is large enough.
  std::optional<uint64_t> allocate(uint64_t size) {
    for (auto it = free_.begin(); it != free_.end(); ++it) {
      if (it->second < size) continue;
      const uint64_t at = it->first, left = it->second - size;
      free_.erase(it);
      if (left) free_[at + size] = left;
      used_ += size;
      return at;
    }
    return std::nullopt;
  }
  void release(uint64_t offset, uint64_t size) {
    used_ -= size;
    auto next = free_.lower_bound(offset);
    if (next != free_.end() && next->first == offset + size) {
      size += next->second;
      next = free_.erase(next);
    }
    if (next != free_.begin()) {
      auto prev = std::prev(next);
      if (prev->first + prev->second == offset) {
        prev->second += size;
        return;
      }
    }
    free_[offset] = size;
  }

 private:
  uint64_t capacity_, used_ = 0;
  std::map<uint64_t, uint64_t> free_;  // offset -> size
};

}  // namespace globe::viewer
