// GlyphAtlas: SDF glyphs (sdf_glyph.hpp) shelf-packed into one single-channel
// image that a renderer uploads as a texture, rows changed since the last
// upload tracked. Glyphs come from Shaper's PlacedGlyph (font, glyph id).
//
// Thread safety: none; get() changes the atlas. Use it from one thread.
#pragma once

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "text/sdf_glyph.hpp"

namespace globe::text {

// SDF glyphs shelf-packed into one single-channel image (top row first), one
// pixel of padding between them; a glyph is rendered once and found again by
// (font, glyph id).
class GlyphAtlas {
 public:
  // x, y: the bitmap's top-left texel in the atlas; the rest as in SdfGlyph
  // (width and height include the SDF border; 0 x 0 for blank glyphs, which
  // take no space).
  struct Entry {
    int x = 0, y = 0, width = 0, height = 0;
    int left = 0, top = 0;
    float advance = 0;
  };

  // Keeps a reference to `sdf` (which must outlive the atlas). width and
  // height > 0 (TextError otherwise).
  GlyphAtlas(const SdfRenderer& sdf, int width = 1024, int height = 1024);

  // The glyph's entry, rendered and packed on first use; nullptr when the
  // atlas is full. The pointer stays valid as long as the atlas.
  const Entry* get(uint16_t font, uint32_t glyph);
  int width() const;
  int height() const;
  const std::vector<uint8_t>& pixels() const;
  // Rows changed since the last clear_dirty() ([y0, y1), empty when none): what to upload.
  std::pair<int, int> dirty_rows() const;
  void clear_dirty();
  size_t glyph_count() const;

 private:
  struct Shelf {
    int y = 0, height = 0, x = 0;  // x: where the next glyph goes
  };
  bool place(int w, int h, int* x, int* y);

  const SdfRenderer& sdf_;
  int width_, height_;
  std::vector<uint8_t> pixels_;
  std::vector<Shelf> shelves_;
  int next_shelf_y_ = 0;
  int dirty_y0_ = 0, dirty_y1_ = 0;
  std::unordered_map<uint64_t, Entry> entries_;
};

}  // namespace globe::text
