// Image tile decoding to RGBA (see rgba_decode.hpp).
#include "runtime/rgba_decode.hpp"

#include <cstring>
#include <stdexcept>

#include "runtime/jpeg_webp_decoders.hpp"
#include "runtime/png_codec.hpp"

namespace globe {

RgbaImage decode_rgba(std::span<const uint8_t> blob) {
  RgbaImage img;
  const uint8_t* d = blob.data();
  const size_t n = blob.size();
  if (n >= 8 && std::memcmp(d, "\x89PNG\r\n\x1a\n", 8) == 0)
    img.rgba = decode_png_rgba(d, n, img.width, img.height);
  else if (n >= 3 && d[0] == 0xff && d[1] == 0xd8 && d[2] == 0xff)
    img.rgba = decode_jpeg_rgba(d, n, img.width, img.height);
  else if (n >= 12 && std::memcmp(d, "RIFF", 4) == 0 && std::memcmp(d + 8, "WEBP", 4) == 0)
    img.rgba = decode_webp_rgba(d, n, img.width, img.height);
  else
    throw std::runtime_error("not a PNG, JPEG or WebP image");
  return img;
}

}  // namespace globe
