// The Unicode bidirectional algorithm for one line, from FriBiDi: the
// paragraph's base direction, each character's embedding level, and the
// visual position of each character. The shaper (shaping.cpp) cuts runs by
// level and orders them by visual position.
#pragma once

#include <cstdint>
#include <vector>

namespace globe::text::detail {

struct BidiLine {
  bool rtl = false;              // the paragraph's base direction (from its first strong character)
  std::vector<uint8_t> levels;   // per character, after rule L1; odd: right to left
  std::vector<uint32_t> visual;  // per character, its position left to right (rule L2)
};

// TextError when FriBiDi fails (out of memory).
BidiLine bidi_line(const std::vector<char32_t>& text);

}  // namespace globe::text::detail
