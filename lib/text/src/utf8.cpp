// decode_utf8: well-formed sequences as in Unicode's table 3-7 (no overlong
// forms, no surrogates, nothing above U+10FFFF); each maximal subpart of an
// ill-formed sequence becomes one U+FFFD.
#include "utf8.hpp"

namespace globe::text::detail {

DecodedText decode_utf8(std::string_view utf8) {
  constexpr char32_t kReplacement = 0xFFFD;
  DecodedText out;
  out.code_points.reserve(utf8.size());
  out.offsets.reserve(utf8.size());
  size_t i = 0;
  while (i < utf8.size()) {
    const auto start = static_cast<uint32_t>(i);
    const auto lead = static_cast<uint8_t>(utf8[i]);
    int length = 0;
    char32_t c = 0;
    uint8_t low = 0x80, high = 0xBF;  // the second byte's range (table 3-7)
    if (lead < 0x80) {
      length = 1, c = lead;
    } else if (lead >= 0xC2 && lead <= 0xDF) {
      length = 2, c = lead & 0x1Fu;
    } else if (lead >= 0xE0 && lead <= 0xEF) {
      length = 3, c = lead & 0x0Fu;
      if (lead == 0xE0) low = 0xA0;   // no overlong forms
      if (lead == 0xED) high = 0x9F;  // no surrogates
    } else if (lead >= 0xF0 && lead <= 0xF4) {
      length = 4, c = lead & 0x07u;
      if (lead == 0xF0) low = 0x90;   // no overlong forms
      if (lead == 0xF4) high = 0x8F;  // nothing above U+10FFFF
    }
    if (length == 0) {  // a continuation byte or C0, C1, F5..FF
      out.code_points.push_back(kReplacement);
      out.offsets.push_back(start);
      ++i;
      continue;
    }
    ++i;
    int read = 1;
    for (; read < length && i < utf8.size(); ++read, ++i) {
      const auto byte = static_cast<uint8_t>(utf8[i]);
      const uint8_t lo = read == 1 ? low : 0x80, hi = read == 1 ? high : 0xBF;
      if (byte < lo || byte > hi) break;
      c = (c << 6) | (byte & 0x3Fu);
    }
    out.code_points.push_back(read == length ? c : kReplacement);
    out.offsets.push_back(start);
  }
  return out;
}

}  // namespace globe::text::detail
