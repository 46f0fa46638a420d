// Text for the viewer (see text_engine.hpp).
#include "data/text_engine.hpp"

#include <cstdio>

#include "runtime/errors.hpp"

namespace globe::viewer {

TextEngine::TextEngine(const std::string& font) {
  try {
    fonts_ = std::make_unique<text::FontSet>(text::FontSet::debian(font));
    shaper_ = std::make_unique<text::Shaper>(*fonts_);
    sdf_ = std::make_unique<text::SdfRenderer>(*fonts_, static_cast<int>(kAtlasPx), 3, 8.0f);
    atlas_ = std::make_unique<text::GlyphAtlas>(*sdf_, 1024, 1024);
  } catch (const text::TextError& e) {
    throw InputError(std::string("text: ") + e.what());
  }
}

TextEngine::~TextEngine() = default;

ShapedString TextEngine::shape(std::string_view utf8) {
  ShapedString s;
  const text::ShapedText t = shaper_->shape(utf8, kAtlasPx);
  s.width = t.width, s.ascent = t.ascent, s.descent = t.descent;
  s.ok = !t.glyphs.empty();
  for (const text::PlacedGlyph& g : t.glyphs) {
    ShapedGlyph sg{g.x, g.y, g.advance, atlas_->get(g.font, g.glyph)};
    if (!sg.atlas) {
      s.ok = false;
      ++atlas_misses_;
      break;
    }
    if (sg.atlas->width == 0) sg.atlas = nullptr;
    s.glyphs.push_back(sg);
  }
  return s;
}

TextEngine* default_text_engine() {
  static std::unique_ptr<TextEngine> engine = [] {
    try {
      return std::make_unique<TextEngine>();
    } catch (const InputError& e) {
      std::fprintf(stderr, "globe-view: %s; legends are drawn without text\n", e.what());
      return std::unique_ptr<TextEngine>();
    }
  }();
  return engine.get();
}

}  // namespace globe::viewer
