// The one wrapper around libjpeg and libwebp in the viewer's path: decodes a
// JPEG or WebP image in memory to 8-bit RGBA rows from the top (the viewer
// decodes image tiles without GDAL, docs/architecture.md rule 2). Both throw
// std::runtime_error naming what is wrong.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace globe {

std::vector<uint8_t> decode_jpeg_rgba(const uint8_t* data, size_t size, int& width, int& height);
std::vector<uint8_t> decode_webp_rgba(const uint8_t* data, size_t size, int& width, int& height);

}  // namespace globe
