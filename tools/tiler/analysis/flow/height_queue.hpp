// A queue of cells by height: the lowest first, the earliest queued first
// among equal heights (a stable priority queue), for searches whose heights
// lie in a known range (a depression: its lowest raw height up to its
// level). Where the range spans at most 65,536 heights or no more heights
// than cells will be queued (so the buckets take at most 8 bytes a cell),
// one FIFO list per height, linked through the order of arrival, and the
// least non-empty one found in a few steps through a bitmap tree (64
// buckets a bit one level up); else a binary heap of (height, arrival)
// keys. Both give the same order. Buffers are kept between searches.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <functional>
#include <vector>

namespace globe::flow {

class HeightQueue {
 public:
  // Empties the queue for heights lowest .. highest, and about `cells`
  // cells.
  void reset(int32_t lowest, int32_t highest, size_t cells) {
    cell_.clear();
    heap_.clear();
    size_ = 0;
    base_ = lowest;
    const uint64_t span = uint64_t(int64_t(highest) - lowest) + 1;
    span_ = span;
    buckets_ = span <= std::max<uint64_t>(uint64_t(1) << 16, cells);
    if (!buckets_) return;
    // Level 0: a bit per bucket; each level above: a bit per word below,
    // up to a single word. All bits are clear after every search (each is
    // cleared as its bucket empties), so only new words need clearing.
    size_t words = size_t((span + 63) / 64), level = 0;
    while (true) {
      if (bits_.size() <= level) bits_.emplace_back();
      if (bits_[level].size() < words) bits_[level].resize(words, 0);
      if (words == 1) break;
      words = (words + 63) / 64;
      ++level;
    }
    levels_ = level + 1;
    if (head_.size() < span) head_.resize(size_t(span)), tail_.resize(size_t(span));
  }

  bool empty() const { return size_ == 0; }

  void push(int32_t height, uint32_t cell) {
    const uint32_t arrival = uint32_t(cell_.size());
    cell_.push_back(cell);
    ++size_;
    if (!buckets_) {
      heap_.push_back((uint64_t(uint32_t(height) ^ 0x80000000u) << 32) | arrival);
      std::push_heap(heap_.begin(), heap_.end(), std::greater<>());
      return;
    }
    if (height < base_ || uint64_t(int64_t(height) - base_) >= span_) {
      to_heap();  // outside the range given: rare (another depression's cell)
      heap_.push_back((uint64_t(uint32_t(height) ^ 0x80000000u) << 32) | arrival);
      std::push_heap(heap_.begin(), heap_.end(), std::greater<>());
      return;
    }
    const size_t b = size_t(int64_t(height) - base_);
    next_.resize(cell_.size());
    if (!has(b)) {
      head_[b] = arrival;
      mark(b);
    } else {
      next_[tail_[b]] = arrival;
    }
    tail_[b] = arrival;
  }

  uint32_t pop() {
    --size_;
    if (!buckets_) {
      std::pop_heap(heap_.begin(), heap_.end(), std::greater<>());
      const uint32_t arrival = uint32_t(heap_.back());
      heap_.pop_back();
      return cell_[arrival];
    }
    size_t b = 0;
    for (size_t l = levels_; l-- > 0;)
      b = b * 64 + size_t(std::countr_zero(bits_[l][b]));
    const uint32_t arrival = head_[b];
    if (arrival == tail_[b])
      unmark(b);
    else
      head_[b] = next_[arrival];
    return cell_[arrival];
  }

 private:
  // The queued cells moved to the heap, with the same keys.
  void to_heap() {
    buckets_ = false;
    while (bits_[levels_ - 1][0] != 0) {
      size_t b = 0;
      for (size_t l = levels_; l-- > 0;)
        b = b * 64 + size_t(std::countr_zero(bits_[l][b]));
      const uint64_t height = uint32_t(int32_t(int64_t(base_) + int64_t(b))) ^ 0x80000000u;
      for (uint32_t a = head_[b];; a = next_[a]) {
        heap_.push_back(height << 32 | a);
        if (a == tail_[b]) break;
      }
      unmark(b);
    }
    std::make_heap(heap_.begin(), heap_.end(), std::greater<>());
  }
  bool has(size_t b) const { return (bits_[0][b / 64] >> (b % 64)) & 1; }
  void mark(size_t b) {
    for (size_t l = 0; l < levels_; ++l, b /= 64) {
      const bool was_empty = bits_[l][b / 64] == 0;
      bits_[l][b / 64] |= uint64_t(1) << (b % 64);
      if (!was_empty) break;
    }
  }
  void unmark(size_t b) {
    for (size_t l = 0; l < levels_; ++l, b /= 64) {
      bits_[l][b / 64] &= ~(uint64_t(1) << (b % 64));
      if (bits_[l][b / 64] != 0) break;
    }
  }

  std::vector<uint32_t> cell_;  // per arrival: the cell
  size_t size_ = 0;
  bool buckets_ = false;
  int32_t base_ = 0;
  uint64_t span_ = 0;
  size_t levels_ = 0;
  std::vector<std::vector<uint64_t>> bits_;
  std::vector<uint32_t> head_, tail_, next_;  // per bucket: first, last; per arrival: next
  std::vector<uint64_t> heap_;                // (height, arrival) keys
};

}  // namespace globe::flow
