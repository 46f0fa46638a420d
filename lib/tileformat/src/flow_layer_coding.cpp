// Codings for the flow layers of analysis blocks (see flow_layer_coding.hpp).
#include "tileformat/flow_layer_coding.hpp"

#include <algorithm>
#include <bit>

#include "tileformat/analysis_block.hpp"

namespace tileformat::flow_coding {

namespace {

// D8 codes 1..8: north, north-east, east .. north-west (x east, y south).
constexpr int kDx[9] = {0, 0, 1, 1, 1, 0, -1, -1, -1};
constexpr int kDy[9] = {0, -1, -1, 0, 1, 1, 1, 0, -1};
constexpr uint8_t kNoNibble = 15;

// The code pointing back: north <-> south, north-east <-> south-west ...
int opposite(int d) {
  return (d + 3) % 8 + 1;
}

std::vector<uint16_t> build_log_add_gains() {
  // 2^(-r/1000) for r = 0..999 in Q30, each from the one before (the step is
  // round(2^(-1/1000) * 2^30)); integers only, so the same everywhere.
  constexpr uint64_t kOne = uint64_t(1) << 30, kStep = 1072997821;
  std::vector<uint64_t> fraction(1000);
  fraction[0] = kOne;
  for (size_t r = 1; r < fraction.size(); ++r)
    fraction[r] = (fraction[r - 1] * kStep + kOne / 2) >> 30;
  std::vector<uint16_t> gains;
  for (uint32_t t = 0;; ++t) {
    const uint64_t x = fraction[t % 1000] >> (t / 1000);  // 2^(-t/1000), Q30
    // log2(1 + x) to 24 bits: square, and a bit is set where it passes 2.
    uint64_t y = kOne + x;
    uint64_t bits = 0;
    if (y >= 2 * kOne) {
      bits = uint64_t(1) << 24;  // 1 + x = 2: log2 is 1
    } else {
      for (int b = 0; b < 24; ++b) {
        y = (y * y) >> 30;
        bits <<= 1;
        if (y >= 2 * kOne) y >>= 1, bits |= 1;
      }
    }
    const uint16_t gain = uint16_t((1000 * bits + (uint64_t(1) << 23)) >> 24);
    if (gain == 0) break;
    gains.push_back(gain);
  }
  return gains;
}

}  // namespace

const std::vector<uint16_t>& log_add_gains() {
  static const std::vector<uint16_t> gains = build_log_add_gains();
  return gains;
}

bool fits_in_nibbles(const std::vector<uint16_t>& values) {
  return std::all_of(values.begin(), values.end(),
                     [](uint16_t v) { return v < kNoNibble || v == kNoValue; });
}

std::vector<uint8_t> pack_nibbles(const std::vector<uint16_t>& values) {
  std::vector<uint8_t> packed((values.size() + 1) / 2, 0);
  for (size_t i = 0; i < values.size(); ++i) {
    const uint8_t code = values[i] == kNoValue ? kNoNibble : uint8_t(values[i]);
    packed[i / 2] |= uint8_t(i % 2 ? code << 4 : code);
  }
  return packed;
}

std::vector<uint16_t> unpack_nibbles(const std::vector<uint8_t>& packed, size_t count) {
  std::vector<uint16_t> values(count);
  for (size_t i = 0; i < count; ++i) {
    const uint8_t code = i % 2 ? packed[i / 2] >> 4 : packed[i / 2] & 15;
    values[i] = code == kNoNibble ? kNoValue : code;
  }
  return values;
}

AreaPredictor::AreaPredictor(const std::vector<uint16_t>& directions, int size)
    : directions_(directions),
      receiver_(directions.size(), -1),
      donors_(directions.size(), 0),
      donor_count_(directions.size(), 0),
      gains_(log_add_gains()) {
  for (int d = 0; d <= 8; ++d)
    step_[d] = ptrdiff_t(kDy[d]) * size + kDx[d];
  size_t i = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x, ++i) {
      // A receiver inside the block (an outlet, a code that is not 1..8, or
      // one off the block has none).
      const uint16_t d = directions[i];
      if (d < 1 || d > 8) continue;
      const int rx = x + kDx[d], ry = y + kDy[d];
      if (rx < 0 || ry < 0 || rx >= size || ry >= size) continue;
      const size_t r = size_t(ry) * size + rx;
      receiver_[i] = int32_t(r);
      donors_[r] |= uint8_t(1 << (opposite(d) - 1));
      ++donor_count_[r];
    }
}

std::optional<std::vector<uint32_t>> AreaPredictor::upstream_first() const {
  const size_t n = directions_.size();
  std::vector<uint8_t> waiting = donor_count_;  // donors not yet in the order
  std::vector<uint32_t> order;
  order.reserve(n);
  for (size_t i = 0; i < n; ++i)
    if (waiting[i] == 0) order.push_back(uint32_t(i));
  // Kahn's order: a cell goes once its donors have gone.
  for (size_t k = 0; k < order.size(); ++k)
    if (const int32_t r = receiver_[order[k]]; r >= 0 && --waiting[size_t(r)] == 0)
      order.push_back(uint32_t(r));
  if (order.size() != n) return std::nullopt;
  return order;
}

bool AreaPredictor::acyclic() const {
  // Walks down from each cell not yet reached until an outlet, a cell of an
  // earlier walk, or (a cycle) a cell of this one: each cell is marked with
  // the number of the walk that reached it.
  std::vector<uint32_t> walk_of(directions_.size(), 0);
  uint32_t walk = 0;
  for (size_t i = 0; i < walk_of.size(); ++i) {
    if (walk_of[i] != 0) continue;
    ++walk;
    int64_t j = int64_t(i);
    while (j >= 0 && walk_of[size_t(j)] == 0) {
      walk_of[size_t(j)] = walk;
      j = receiver_[size_t(j)];
    }
    if (j >= 0 && walk_of[size_t(j)] == walk) return false;
  }
  return true;
}

uint16_t AreaPredictor::source_value(const std::vector<uint16_t>& values) const {
  // Counted in a table kept per thread, cleared where used; runs of one
  // value (most sources share their cell's area) counted in a register.
  thread_local std::vector<uint32_t> count(size_t(kNoValue) + 1, 0);
  std::vector<uint16_t> seen;
  uint16_t run_value = 0;
  uint32_t run = 0;
  auto flush = [&] {
    if (run == 0) return;
    if (count[run_value] == 0) seen.push_back(run_value);
    count[run_value] += run;
  };
  for (size_t i = 0; i < values.size(); ++i) {
    if (donors_[i] || directions_[i] == kNoValue || values[i] == kNoValue) continue;
    if (values[i] != run_value) {
      flush();
      run_value = values[i];
      run = 0;
    }
    ++run;
  }
  flush();
  // The most common, the least of those on ties.
  uint16_t best = 0;
  uint32_t best_count = 0;
  for (uint16_t v : seen) {
    if (count[v] > best_count || (count[v] == best_count && v < best))
      best = v, best_count = count[v];
    count[v] = 0;
  }
  return best;
}

}  // namespace tileformat::flow_coding
