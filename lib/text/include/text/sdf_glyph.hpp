// SdfRenderer: a FontSet's glyphs as single-channel signed distance fields in
// MapLibre's convention, computed exactly from the outlines FreeType loads
// (src/sdf_glyph.cpp says why not FT_RENDER_MODE_SDF: 40 times slower, and
// wrong at some corners; the tests check the two agree elsewhere). Users:
// glyph_atlas.hpp (the viewer's atlas) and glyph_pbf.hpp (MapLibre's PBFs).
// No FreeType types here.
//
// Thread safety: an SdfRenderer opens its own FreeType faces; glyph() and
// codepoint() lock a mutex of the renderer, so concurrent calls are safe but
// serialized. For parallel rendering use one SdfRenderer per thread (they
// may share the FontSet).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "text/font_set.hpp"

namespace globe::text {

// A glyph's signed distance field, single channel, MapLibre's convention:
// rendered at size_px per em with `border` pixels of margin on every side;
// a texel's value v = 255 - 255 * (d / radius + 0.25) clamped to 0..255,
// d the signed distance in pixels to the outline (negative inside), so the
// outline is at 191.25 (MapLibre's 0.75 cutoff) and radius = 8 pixels by default.
struct SdfGlyph {
  int width = 0,
      height = 0;         // of the bitmap, border included (0 x 0 for blank glyphs such as space)
  int left = 0, top = 0;  // bitmap's left edge right of the pen, top edge above the baseline,
                          // pixels (FreeType's bitmap_left/top minus the border / plus the border)
  float advance = 0;      // pixels
  std::vector<uint8_t> pixels;  // width*height, top row first
};

class SdfRenderer {
 public:
  // Keeps a reference to `fonts` (which must outlive the renderer) and opens
  // its own FreeType faces. Glyphs are loaded unhinted, as node-fontnik loads
  // them. size_px in 1..1000, border and radius in 0..64 and 1..64 pixels:
  // TextError otherwise.
  SdfRenderer(const FontSet& fonts, int size_px = 24, int border = 3, float radius = 8);
  ~SdfRenderer();
  SdfRenderer(const SdfRenderer&) = delete;
  SdfRenderer& operator=(const SdfRenderer&) = delete;

  int size_px() const;
  int border() const;
  float radius() const;
  const FontSet& fonts() const;

  // The field of FreeType's unhinted outline in the convention above, over
  // the box FT_RENDER_MODE_SDF would render (its control box on the pixel
  // grid, plus the border). TextError for a font index or glyph id the font
  // does not have. A glyph without an outline (bitmap-only fonts) is blank.
  SdfGlyph glyph(uint16_t font, uint32_t glyph_id) const;
  // The glyph of Unicode code point c from the first font that has it (MapLibre
  // glyph PBFs are by code point); nullopt when no font has it.
  std::optional<SdfGlyph> codepoint(char32_t c, uint32_t* glyph_id = nullptr,
                                    uint16_t* font = nullptr) const;
  // FreeType's ascender of the font at size_px, whole pixels (the 26.6 value
  // truncated, as node-fontnik reads it): glyph PBFs give `top` below it.
  int ascender_px(uint16_t font) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace globe::text
