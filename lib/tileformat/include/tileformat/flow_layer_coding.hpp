// The two codings of analysis blocks made for the flow layers
// (docs/tileformat.md §9): D8 codes packed two to a byte, and upstream areas
// predicted along the flow directions of the same block. Used by the
// analysis block codec (analysis_block.hpp is the API; this is its part).
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "tileformat/analysis_block.hpp"

namespace tileformat::flow_coding {

// Values 0..14 and kNoValue as 4-bit codes (15: no value), two to a byte,
// the first sample in the low half; false where some value does not fit.
bool fits_in_nibbles(const std::vector<uint16_t>& values);
std::vector<uint8_t> pack_nibbles(const std::vector<uint16_t>& values);
std::vector<uint16_t> unpack_nibbles(const std::vector<uint8_t>& packed, size_t count);

// The prediction of quantized upstream areas from a block's D8 codes: each
// cell's area from its donors' (the neighbours whose code points at it) and
// its own (`source`), summed in the log domain.
class AreaPredictor {
 public:
  AreaPredictor(const std::vector<uint16_t>& directions, int size);

  // The block's cells (row-major indices), each after its donors; nullopt
  // where the directions form a cycle.
  std::optional<std::vector<uint32_t>> upstream_first() const;
  // Whether the directions form no cycle (what upstream_first finds, for
  // less).
  bool acyclic() const;
  // The most common value of the cells without donors (the area of one
  // sample, at the finest zoom), the least of those on ties.
  uint16_t source_value(const std::vector<uint16_t>& values) const;
  // The value predicted for cell i from its donors' `values` (inline: the
  // encoder calls it for every sample).
  uint16_t predict(const std::vector<uint16_t>& values, size_t i, uint16_t source) const {
    if (directions_[i] == kNoValue) return kNoValue;
    uint32_t p = source;
    // Donors in code order (north first); each lies in the block.
    for (unsigned mask = donors_[i]; mask; mask &= mask - 1) {
      const uint16_t q = values[size_t(ptrdiff_t(i) + step_[std::countr_zero(mask) + 1])];
      if (q == kNoValue) continue;
      const uint32_t t = p > q ? p - q : q - p;
      p = std::max<uint32_t>(p, q) + (t < gains_.size() ? gains_[t] : 0);
    }
    return uint16_t(std::min<uint32_t>(p, kNoValue - 1));
  }

 private:
  const std::vector<uint16_t>& directions_;
  std::vector<int32_t> receiver_;     // per cell: the cell it drains into in the block, or -1
  std::vector<uint8_t> donors_;       // per cell: bit d - 1 where the neighbour at code d drains in
  std::vector<uint8_t> donor_count_;  // per cell: bits set in donors_
  ptrdiff_t step_[9];                 // index offset of the neighbour at each code
  const std::vector<uint16_t>& gains_;
};

// round(1000 log2(1 + 2^(-t/1000))) for t = 0 until it is 0: the quanta a
// log-quantized area gains when one t quanta below it is added. Computed in
// integers, so that every machine builds the same table.
const std::vector<uint16_t>& log_add_gains();

}  // namespace tileformat::flow_coding
