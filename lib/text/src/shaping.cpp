// Shaper: HarfBuzz, called from here only. A line is decoded (utf8.cpp),
// given bidi levels and visual positions (bidi.cpp), cut into items of one
// level, script and font, and each item is shaped with the whole line as
// context (so Arabic joins across a font change); the items are laid left to
// right in FriBiDi's visual order. Positions are computed at the fonts' units
// per em and scaled to pixels, so they do not depend on hinting.
#include "text/shaping.hpp"

#include <hb.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "bidi.hpp"
#include "utf8.hpp"

namespace globe::text {
namespace {

// A script's usual language: what a run is shaped with when the caller set
// none, so localized forms never follow the process locale.
const char* default_language(hb_script_t script) {
  switch (script) {
    case HB_SCRIPT_LATIN:
      return "en";
    case HB_SCRIPT_GREEK:
      return "el";
    case HB_SCRIPT_CYRILLIC:
      return "ru";
    case HB_SCRIPT_ARABIC:
      return "ar";
    case HB_SCRIPT_HEBREW:
      return "he";
    case HB_SCRIPT_DEVANAGARI:
      return "hi";
    case HB_SCRIPT_BENGALI:
      return "bn";
    case HB_SCRIPT_THAI:
      return "th";
    case HB_SCRIPT_GEORGIAN:
      return "ka";
    case HB_SCRIPT_ARMENIAN:
      return "hy";
    case HB_SCRIPT_ETHIOPIC:
      return "am";
    case HB_SCRIPT_HAN:
      return "zh";
    case HB_SCRIPT_HIRAGANA:
    case HB_SCRIPT_KATAKANA:
      return "ja";
    case HB_SCRIPT_HANGUL:
      return "ko";
    default:
      return "und";
  }
}

bool is_neutral(hb_script_t script) {
  return script == HB_SCRIPT_COMMON || script == HB_SCRIPT_INHERITED || script == HB_SCRIPT_UNKNOWN;
}

// Joiners and variation selectors belong to the character before them.
bool is_attached(char32_t c, hb_script_t script) {
  return script == HB_SCRIPT_INHERITED || c == 0x200C || c == 0x200D ||
         (c >= 0xFE00 && c <= 0xFE0F);
}

struct Item {
  size_t start = 0, length = 0;
  uint8_t level = 0;
  hb_script_t script = HB_SCRIPT_COMMON;
  uint16_t font = 0;
  uint32_t visual = 0;  // visual position of its leftmost character
};

}  // namespace

struct Shaper::Impl {
  const FontSet& fonts;
  std::vector<hb_font_t*> hb_fonts;
  std::vector<float> units_per_em;
  std::string language;

  explicit Impl(const FontSet& f) : fonts(f) {}
  ~Impl() {
    for (hb_font_t* font : hb_fonts)
      hb_font_destroy(font);
  }
};

Shaper::Shaper(const FontSet& fonts) : impl_(std::make_unique<Impl>(fonts)) {
  for (size_t i = 0; i < fonts.size(); ++i) {
    hb_blob_t* blob = hb_blob_create_from_file_or_fail(fonts.path(i).c_str());
    if (blob == nullptr) {
      throw TextError(fonts.path(i) + ": HarfBuzz cannot read the font file; check it is readable");
    }
    hb_face_t* face = hb_face_create(blob, 0);
    hb_blob_destroy(blob);
    const unsigned upem = hb_face_get_upem(face);
    hb_font_t* font = hb_font_create(face);  // OpenType functions, scale = units per em
    hb_face_destroy(face);
    hb_font_make_immutable(font);
    impl_->hb_fonts.push_back(font);
    impl_->units_per_em.push_back(static_cast<float>(upem));
  }
}

Shaper::~Shaper() = default;

void Shaper::set_language(std::string bcp47) {
  impl_->language = std::move(bcp47);
}

ShapedText Shaper::shape(std::string_view utf8, float size_px) const {
  if (!(size_px > 0) || !std::isfinite(size_px)) {
    throw TextError("Shaper::shape: size_px must be positive, got " + std::to_string(size_px));
  }
  ShapedText out;
  const detail::DecodedText text = detail::decode_utf8(utf8);
  const size_t n = text.code_points.size();
  if (n == 0) return out;
  const detail::BidiLine bidi = detail::bidi_line(text.code_points);
  out.rtl = bidi.rtl;

  // Scripts: neutral characters take the script before them (the first real
  // script for those at the start).
  hb_unicode_funcs_t* unicode = hb_unicode_funcs_get_default();
  std::vector<hb_script_t> raw(n), script(n);
  for (size_t i = 0; i < n; ++i)
    raw[i] = hb_unicode_script(unicode, text.code_points[i]);
  hb_script_t current = HB_SCRIPT_COMMON;
  for (size_t i = 0; i < n && current == HB_SCRIPT_COMMON; ++i) {
    if (!is_neutral(raw[i])) current = raw[i];
  }
  for (size_t i = 0; i < n; ++i) {
    if (!is_neutral(raw[i])) current = raw[i];
    script[i] = current;
  }

  // Fonts: the first of the chain that has the character; neutral characters
  // stay in the font before them when it has them, marks and joiners always.
  const FontSet& fonts = impl_->fonts;
  std::vector<uint16_t> font(n);
  for (size_t i = 0; i < n; ++i) {
    const char32_t c = text.code_points[i];
    if (i > 0 && (is_attached(c, raw[i]) || (is_neutral(raw[i]) && fonts.has(font[i - 1], c)))) {
      font[i] = font[i - 1];
    } else {
      font[i] = static_cast<uint16_t>(std::max(fonts.font_for(c), 0));  // none: .notdef of font 0
    }
  }

  std::vector<Item> items;
  for (size_t i = 0; i < n; ++i) {
    if (items.empty() || bidi.levels[i] != items.back().level || script[i] != items.back().script ||
        font[i] != items.back().font) {
      items.push_back({i, 0, bidi.levels[i], script[i], font[i], bidi.visual[i]});
    }
    items.back().length++;
    items.back().visual = std::min(items.back().visual, bidi.visual[i]);
  }
  std::sort(items.begin(), items.end(),
            [](const Item& a, const Item& b) { return a.visual < b.visual; });

  std::vector<uint32_t> codes(text.code_points.begin(), text.code_points.end());
  std::vector<bool> used(fonts.size(), false);
  const std::unique_ptr<hb_buffer_t, decltype(&hb_buffer_destroy)> owned(hb_buffer_create(),
                                                                         hb_buffer_destroy);
  hb_buffer_t* buffer = owned.get();
  float pen = 0;
  for (const Item& item : items) {
    hb_buffer_clear_contents(buffer);
    hb_buffer_add_utf32(buffer, codes.data(), static_cast<int>(n),
                        static_cast<unsigned>(item.start), static_cast<int>(item.length));
    hb_buffer_set_direction(buffer, item.level % 2 == 1 ? HB_DIRECTION_RTL : HB_DIRECTION_LTR);
    hb_buffer_set_script(buffer, item.script);
    const char* language =
        impl_->language.empty() ? default_language(item.script) : impl_->language.c_str();
    hb_buffer_set_language(buffer, hb_language_from_string(language, -1));
    unsigned flags = HB_BUFFER_FLAG_DEFAULT;
    if (item.start == 0) flags |= HB_BUFFER_FLAG_BOT;
    if (item.start + item.length == n) flags |= HB_BUFFER_FLAG_EOT;
    hb_buffer_set_flags(buffer, static_cast<hb_buffer_flags_t>(flags));
    hb_shape(impl_->hb_fonts[item.font], buffer, nullptr, 0);
    if (!hb_buffer_allocation_successful(buffer)) {
      throw TextError("HarfBuzz: out of memory shaping a " + std::to_string(utf8.size()) +
                      "-byte label");
    }
    used[item.font] = true;
    const float scale = size_px / impl_->units_per_em[item.font];
    unsigned count = 0;
    const hb_glyph_info_t* info = hb_buffer_get_glyph_infos(buffer, &count);
    const hb_glyph_position_t* pos = hb_buffer_get_glyph_positions(buffer, &count);
    for (unsigned g = 0; g < count; ++g) {
      PlacedGlyph placed;
      placed.font = item.font;
      placed.glyph = info[g].codepoint;
      placed.x = pen + static_cast<float>(pos[g].x_offset) * scale;
      placed.y = static_cast<float>(pos[g].y_offset) * scale;
      placed.advance = static_cast<float>(pos[g].x_advance) * scale;
      placed.cluster = text.offsets[std::min<size_t>(info[g].cluster, n - 1)];
      out.glyphs.push_back(placed);
      pen += placed.advance;
    }
  }
  out.width = pen;

  for (size_t f = 0; f < fonts.size(); ++f) {
    hb_font_extents_t extents{};
    if (!used[f] || !hb_font_get_h_extents(impl_->hb_fonts[f], &extents)) continue;
    const float scale = size_px / impl_->units_per_em[f];
    out.ascent = std::max(out.ascent, static_cast<float>(extents.ascender) * scale);
    out.descent = std::max(out.descent, static_cast<float>(-extents.descender) * scale);
  }
  return out;
}

}  // namespace globe::text
