// bidi_line: FriBiDi, called from here only — character types and bracket
// pairs, the paragraph's embedding levels with its direction found from the
// text (FRIBIDI_PAR_ON), then the line reordered (rules L1 and L2) without
// mirroring or shaping, which HarfBuzz does per run.
#include "bidi.hpp"

#include <fribidi.h>

#include "text/font_set.hpp"

namespace globe::text::detail {

BidiLine bidi_line(const std::vector<char32_t>& text) {
  BidiLine out;
  if (text.empty()) return out;
  const auto length = static_cast<FriBidiStrIndex>(text.size());
  const std::vector<FriBidiChar> chars(text.begin(), text.end());
  std::vector<FriBidiCharType> types(text.size());
  std::vector<FriBidiBracketType> brackets(text.size());
  std::vector<FriBidiLevel> levels(text.size());
  fribidi_get_bidi_types(chars.data(), length, types.data());
  fribidi_get_bracket_types(chars.data(), length, types.data(), brackets.data());
  FriBidiParType direction = FRIBIDI_PAR_ON;
  if (fribidi_get_par_embedding_levels_ex(types.data(), brackets.data(), length, &direction,
                                          levels.data()) == 0) {
    throw TextError("FriBiDi: cannot find the embedding levels of a " +
                    std::to_string(text.size()) + "-character label (out of memory?)");
  }
  std::vector<FriBidiStrIndex> map(text.size());
  for (size_t i = 0; i < map.size(); ++i)
    map[i] = static_cast<FriBidiStrIndex>(i);
  // Flags 0: no mark reordering, no shaping; levels get rule L1 in place.
  if (fribidi_reorder_line(0, types.data(), length, 0, direction, levels.data(), nullptr,
                           map.data()) == 0) {
    throw TextError("FriBiDi: cannot reorder a " + std::to_string(text.size()) +
                    "-character label (out of memory?)");
  }
  out.rtl = FRIBIDI_IS_RTL(direction);
  out.levels.assign(levels.begin(), levels.end());
  out.visual.resize(text.size());
  for (size_t v = 0; v < map.size(); ++v)
    out.visual[static_cast<size_t>(map[v])] = static_cast<uint32_t>(v);
  return out;
}

}  // namespace globe::text::detail
