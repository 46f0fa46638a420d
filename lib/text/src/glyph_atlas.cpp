// GlyphAtlas: shelf packing. A glyph goes on the first shelf that is tall
// enough without wasting more than a third of its height and has room left;
// otherwise a new shelf of the glyph's height opens below the last one. Each
// glyph takes its size plus one pixel right and below (the padding, left at
// 0: far outside in the SDF). Full: get() returns nullptr and the atlas is
// unchanged — the caller clears it or makes a bigger one.
#include "text/glyph_atlas.hpp"

#include <algorithm>
#include <cstring>

namespace globe::text {

GlyphAtlas::GlyphAtlas(const SdfRenderer& sdf, int width, int height)
    : sdf_(sdf), width_(width), height_(height) {
  if (width <= 0 || height <= 0) {
    throw TextError("GlyphAtlas: size must be positive, got " + std::to_string(width) + " x " +
                    std::to_string(height));
  }
  pixels_.assign(static_cast<size_t>(width) * static_cast<size_t>(height), 0);
}

bool GlyphAtlas::place(int w, int h, int* x, int* y) {
  const int need_w = w + 1, need_h = h + 1;  // one pixel of padding
  Shelf* best = nullptr;
  for (Shelf& shelf : shelves_) {
    const bool fits =
        shelf.height >= need_h && shelf.height * 2 <= need_h * 3 && shelf.x + w <= width_;
    if (fits && (best == nullptr || shelf.height < best->height)) best = &shelf;
  }
  if (best == nullptr) {
    if (next_shelf_y_ + h > height_ || w > width_) return false;
    shelves_.push_back({next_shelf_y_, need_h, 0});
    next_shelf_y_ += need_h;
    best = &shelves_.back();
  }
  *x = best->x;
  *y = best->y;
  best->x += need_w;
  return true;
}

const GlyphAtlas::Entry* GlyphAtlas::get(uint16_t font, uint32_t glyph) {
  const uint64_t key = (static_cast<uint64_t>(font) << 32) | glyph;
  if (auto found = entries_.find(key); found != entries_.end()) return &found->second;
  const SdfGlyph sdf = sdf_.glyph(font, glyph);
  Entry entry;
  entry.width = sdf.width;
  entry.height = sdf.height;
  entry.left = sdf.left;
  entry.top = sdf.top;
  entry.advance = sdf.advance;
  if (sdf.width > 0 && sdf.height > 0) {
    if (!place(sdf.width, sdf.height, &entry.x, &entry.y)) return nullptr;
    for (int row = 0; row < sdf.height; ++row) {
      std::memcpy(pixels_.data() + static_cast<size_t>(entry.y + row) * width_ + entry.x,
                  sdf.pixels.data() + static_cast<size_t>(row) * sdf.width,
                  static_cast<size_t>(sdf.width));
    }
    if (dirty_y0_ == dirty_y1_) {
      dirty_y0_ = entry.y, dirty_y1_ = entry.y + sdf.height;
    } else {
      dirty_y0_ = std::min(dirty_y0_, entry.y);
      dirty_y1_ = std::max(dirty_y1_, entry.y + sdf.height);
    }
  }
  return &entries_.emplace(key, entry).first->second;
}

int GlyphAtlas::width() const {
  return width_;
}
int GlyphAtlas::height() const {
  return height_;
}
const std::vector<uint8_t>& GlyphAtlas::pixels() const {
  return pixels_;
}
std::pair<int, int> GlyphAtlas::dirty_rows() const {
  return {dirty_y0_, dirty_y1_};
}
void GlyphAtlas::clear_dirty() {
  dirty_y0_ = dirty_y1_ = 0;
}
size_t GlyphAtlas::glyph_count() const {
  return entries_.size();
}

}  // namespace globe::text
