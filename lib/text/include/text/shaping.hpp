// Shaper: one line of label text laid out as positioned glyphs of a FontSet —
// bidi paragraph direction and visual run order (FriBiDi), runs split by
// script and font coverage, each shaped by HarfBuzz. No HarfBuzz types here.
// The glyphs it places are drawn from sdf_glyph.hpp / glyph_atlas.hpp.
//
// Thread safety: shape() is const and may be called from several threads on
// one Shaper (each call has its own HarfBuzz buffer; the HarfBuzz fonts are
// not changed after construction). set_language() is not: call it before
// sharing the Shaper. One Shaper per thread is always fine.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "text/font_set.hpp"

namespace globe::text {

struct PlacedGlyph {
  uint16_t font = 0;     // index into the FontSet
  uint32_t glyph = 0;    // glyph id in that font
  float x = 0, y = 0;    // pen position of its origin, pixels, baseline y = 0, y up
  float advance = 0;     // pixels
  uint32_t cluster = 0;  // byte offset of its character in the UTF-8 text
};

struct ShapedText {
  std::vector<PlacedGlyph> glyphs;  // in visual order, left to right
  float width = 0;                  // total advance, pixels
  float ascent = 0, descent = 0;    // of the fonts used, pixels, both >= 0
  bool rtl = false;                 // the paragraph's base direction is right-to-left
};

// One line of text: FriBiDi for the paragraph direction and visual order of
// the runs; runs split by script (hb_unicode_script) and by font coverage
// (FontSet::font_for), each shaped by HarfBuzz with its script, direction and
// language; sizes in pixels at size_px per em. Invalid UTF-8 is replaced by
// U+FFFD, never a crash. Characters no font has: the first font's .notdef.
//
// Script-neutral characters (spaces, punctuation, digits: Unicode's Common
// and Inherited scripts) join the run before them, and stay in its font when
// that font has them, so "नई दिल्ली" is one run of the Devanagari font as
// hb-shape shapes it.
class Shaper {
 public:
  // Keeps a reference to `fonts` (which must outlive the Shaper) and opens a
  // HarfBuzz font per file; TextError when HarfBuzz cannot read one.
  explicit Shaper(const FontSet& fonts);
  ~Shaper();
  Shaper(const Shaper&) = delete;
  Shaper& operator=(const Shaper&) = delete;

  // The language every run is shaped with, a BCP 47 tag ("mr", "sr", "ur"):
  // it picks a font's localized forms. Empty (the default): each run gets the
  // usual language of its script (Devanagari "hi", Arabic "ar", Cyrillic "ru",
  // ...), so the result never depends on the process locale.
  void set_language(std::string bcp47);

  // size_px > 0 (TextError otherwise). An empty text gives no glyphs.
  ShapedText shape(std::string_view utf8, float size_px) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace globe::text
