// Codings for the flow layers of analysis blocks (see flow_layer_coding.hpp).
#include "flow_layer_coding.hpp"

#include <algorithm>

#include "tileformat/analysis_block.hpp"

namespace tileformat::flow_coding {

namespace {

// D8 codes 1..8: north, north-east, east .. north-west (x east, y south).
constexpr int kDx[9] = {0, 0, 1, 1, 1, 0, -1, -1, -1};
constexpr int kDy[9] = {0, -1, -1, 0, 1, 1, 1, 0, -1};
constexpr uint8_t kNoNibble = 15;

// The code pointing back: north <-> south, north-east <-> south-west ...
uint16_t opposite(int d) {
  return uint16_t((d + 3) % 8 + 1);
}

// The receiver of cell i inside the block, or -1 (an outlet, a code that is
// not 1..8, or a receiver off the block).
int64_t receiver(const std::vector<uint16_t>& directions, int size, size_t i) {
  const uint16_t d = directions[i];
  if (d < 1 || d > 8) return -1;
  const int x = int(i % size_t(size)) + kDx[d], y = int(i / size_t(size)) + kDy[d];
  if (x < 0 || y < 0 || x >= size || y >= size) return -1;
  return int64_t(y) * size + x;
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

uint32_t log_add(uint32_t a, uint32_t b) {
  return std::max(a, b) + log_add_gain(a > b ? a - b : b - a);
}

}  // namespace

uint16_t log_add_gain(uint32_t t) {
  static const std::vector<uint16_t> gains = build_log_add_gains();
  return t < gains.size() ? gains[t] : 0;
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

std::optional<std::vector<uint32_t>> upstream_first(const std::vector<uint16_t>& directions,
                                                    int size) {
  const size_t n = directions.size();
  std::vector<uint8_t> donors(n, 0);
  for (size_t i = 0; i < n; ++i)
    if (const int64_t r = receiver(directions, size, i); r >= 0) ++donors[size_t(r)];
  // Kahn's order: a cell goes once its donors have gone.
  std::vector<uint32_t> order;
  order.reserve(n);
  for (size_t i = 0; i < n; ++i)
    if (donors[i] == 0) order.push_back(uint32_t(i));
  for (size_t k = 0; k < order.size(); ++k)
    if (const int64_t r = receiver(directions, size, order[k]); r >= 0 && --donors[size_t(r)] == 0)
      order.push_back(uint32_t(r));
  if (order.size() != n) return std::nullopt;
  return order;
}

uint16_t source_value(const std::vector<uint16_t>& directions, const std::vector<uint16_t>& values,
                      int size) {
  std::vector<uint8_t> has_donor(values.size(), 0);
  for (size_t i = 0; i < values.size(); ++i)
    if (const int64_t r = receiver(directions, size, i); r >= 0) has_donor[size_t(r)] = 1;
  std::vector<uint16_t> sources;
  for (size_t i = 0; i < values.size(); ++i)
    if (!has_donor[i] && directions[i] != kNoValue && values[i] != kNoValue)
      sources.push_back(values[i]);
  std::sort(sources.begin(), sources.end());
  uint16_t best = 0;
  size_t best_run = 0;
  for (size_t i = 0; i < sources.size();) {
    size_t j = i;
    while (j < sources.size() && sources[j] == sources[i])
      ++j;
    if (j - i > best_run) best = sources[i], best_run = j - i;
    i = j;
  }
  return best;
}

uint16_t predicted_area(const std::vector<uint16_t>& directions,
                        const std::vector<uint16_t>& values, int size, size_t i, uint16_t source) {
  if (directions[i] == kNoValue) return kNoValue;
  const int x = int(i % size_t(size)), y = int(i / size_t(size));
  uint32_t p = source;
  for (int d = 1; d <= 8; ++d) {
    const int nx = x + kDx[d], ny = y + kDy[d];
    if (nx < 0 || ny < 0 || nx >= size || ny >= size) continue;
    const size_t j = size_t(ny) * size + nx;
    if (directions[j] == opposite(d) && values[j] != kNoValue) p = log_add(p, values[j]);
  }
  return uint16_t(std::min<uint32_t>(p, kNoValue - 1));
}

}  // namespace tileformat::flow_coding
