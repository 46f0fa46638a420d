// Image tile pixels and their PNG / JPEG / WebP encoding (PNG through
// libpng, the others through GDAL's drivers on in-memory files; decoding
// through GDAL) (docs/tileformat.md §8). Thread-safe: every call uses its own
// /vsimem/ file.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "tileformat/image_tile.hpp"

namespace globe {

// A square tile of `size` x `size` pixels: `colour` planes (1 gray or 3 RGB)
// then one alpha plane, each size * size bytes, rows from the north.
struct TilePixels {
  int size = 0;
  int colour = 3;
  std::vector<uint8_t> planes;

  TilePixels() = default;
  TilePixels(int size_, int colour_)
      : size(size_), colour(colour_), planes(size_t(colour_ + 1) * size_ * size_, 0) {}
  size_t plane_size() const { return size_t(size) * size; }
  uint8_t* plane(int c) { return planes.data() + c * plane_size(); }
  const uint8_t* plane(int c) const { return planes.data() + c * plane_size(); }
  const uint8_t* alpha() const { return plane(colour); }
  bool empty() const;   // every pixel transparent
  bool opaque() const;  // every pixel fully opaque
};

struct EncodeOptions {
  tileformat::ImageFormat format = tileformat::ImageFormat::kPng;
  int quality = 85;   // JPEG / WebP; WebP 100 = lossless
  int png_level = 1;  // PNG effort, see encode_png (docs/imagery.md "Encoding")
};

// Encodes a non-empty tile. Opaque tiles drop the alpha channel. JPEG has no
// alpha: a JPEG tile with transparent pixels is written as PNG instead (readers
// identify each tile by its header; GDAL does). WebP gray becomes RGB.
std::vector<uint8_t> encode_image_tile(const TilePixels& px, const EncodeOptions& options);

// Decodes a PNG/JPEG/WebP tile into `colour` planes plus alpha (gray tiles
// are replicated into RGB when colour is 3). Throws FormatError(§8) naming
// what is wrong: not an image, undecodable, not size x size, RGB in a gray
// package.
TilePixels decode_image_tile(std::span<const uint8_t> blob, int size, int colour);

}  // namespace globe
