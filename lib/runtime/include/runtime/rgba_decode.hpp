// Decodes an image tile (PNG, JPEG or WebP, recognised by its first bytes,
// as readers of MBTiles do) to 8-bit RGBA without GDAL: what the viewer
// drapes. Throws std::runtime_error naming what is wrong.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace globe {

struct RgbaImage {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;  // rows from the top, 4 bytes per pixel
};

RgbaImage decode_rgba(std::span<const uint8_t> blob);

}  // namespace globe
