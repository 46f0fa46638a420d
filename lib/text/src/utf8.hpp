// UTF-8 decoding for the shaper: code points with the byte offset each came
// from, invalid input replaced by U+FFFD as Unicode 15 section 3.9
// ("U+FFFD Substitution of Maximal Subparts") recommends, never a crash.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

namespace globe::text::detail {

struct DecodedText {
  std::vector<char32_t> code_points;
  std::vector<uint32_t> offsets;  // byte offset of each code point in the input
};

DecodedText decode_utf8(std::string_view utf8);

}  // namespace globe::text::detail
