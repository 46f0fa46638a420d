// Text for the viewer (labels, legends, overlays): lib/text's font chain,
// shaper, SDF glyphs and atlas in one place - a string becomes glyphs with
// their atlas entries, at the atlas's size (kAtlasPx per em). One per font
// choice; the legends share default_text_engine(). Not thread safe (the
// atlas grows as new glyphs are met); the viewer uses it from its GL thread.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "text/font_set.hpp"
#include "text/glyph_atlas.hpp"
#include "text/sdf_glyph.hpp"
#include "text/shaping.hpp"

namespace globe::viewer {

// One glyph of a shaped string, at the atlas's size.
struct ShapedGlyph {
  float x = 0;  // pen position from the text's start, px at kAtlasPx
  float y = 0;  // from the baseline, up
  float advance = 0;
  const text::GlyphAtlas::Entry* atlas = nullptr;  // nullptr: blank (a space)
};

struct ShapedString {
  std::vector<ShapedGlyph> glyphs;
  float width = 0, ascent = 0, descent = 0;  // px at kAtlasPx
  bool ok = false;                           // shaped and every glyph in the atlas
};

class TextEngine {
 public:
  static constexpr float kAtlasPx = 24;  // the SDF glyphs' size per em (MapLibre's)
  // `font`: a file tried before Debian's Noto and DejaVu chain ("" none).
  // Throws InputError for an unreadable font or no fonts at all.
  explicit TextEngine(const std::string& font = "");
  ~TextEngine();
  ShapedString shape(std::string_view utf8);
  text::GlyphAtlas& atlas() { return *atlas_; }
  // Strings whose glyphs did not fit the atlas.
  size_t atlas_misses() const { return atlas_misses_; }

 private:
  std::unique_ptr<text::FontSet> fonts_;
  std::unique_ptr<text::Shaper> shaper_;
  std::unique_ptr<text::SdfRenderer> sdf_;
  std::unique_ptr<text::GlyphAtlas> atlas_;
  size_t atlas_misses_ = 0;
};

// The engine of Debian's default chain, made on first use; nullptr (after a
// note on stderr, once) where no font is installed: legends then go without
// their text rather than the viewer without its picture.
TextEngine* default_text_engine();

}  // namespace globe::viewer
