// The two codings of analysis blocks made for the flow layers
// (docs/tileformat.md §9): D8 codes packed two to a byte, and upstream areas
// predicted along the flow directions of the same block. Private to the
// analysis block codec.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

namespace tileformat::flow_coding {

// Values 0..14 and kNoValue as 4-bit codes (15: no value), two to a byte,
// the first sample in the low half; false where some value does not fit.
bool fits_in_nibbles(const std::vector<uint16_t>& values);
std::vector<uint8_t> pack_nibbles(const std::vector<uint16_t>& values);
std::vector<uint16_t> unpack_nibbles(const std::vector<uint8_t>& packed, size_t count);

// The block's cells (row-major indices), every cell after the cells that
// drain into it (its donors: the neighbours whose D8 code in `directions`
// points at it); nullopt where the directions form a cycle.
std::optional<std::vector<uint32_t>> upstream_first(const std::vector<uint16_t>& directions,
                                                    int size);

// The most common quantized area of the cells without donors (the area of
// one sample, at the finest zoom), the least of the most common.
uint16_t source_value(const std::vector<uint16_t>& directions, const std::vector<uint16_t>& values,
                      int size);

// The quantized area predicted for cell i from its donors' values (and
// `source` for the cell's own area), summed in the log domain: see §9.
uint16_t predicted_area(const std::vector<uint16_t>& directions,
                        const std::vector<uint16_t>& values, int size, size_t i, uint16_t source);

// round(1000 log2(1 + 2^(-t/1000))): the quanta a log-quantized area gains
// when one t quanta below it is added. Computed in integers, so that every
// machine builds the same table.
uint16_t log_add_gain(uint32_t t);

}  // namespace tileformat::flow_coding
