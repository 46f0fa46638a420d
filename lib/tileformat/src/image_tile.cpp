// Image tile headers (see image_tile.hpp, docs/tileformat.md §8).
#include "tileformat/image_tile.hpp"

#include <cstring>

#include "tileformat/error.hpp"

namespace tileformat {
namespace {

uint32_t be32(const uint8_t* p) {
  return uint32_t{p[0]} << 24 | uint32_t{p[1]} << 16 | uint32_t{p[2]} << 8 | p[3];
}
uint32_t be16(const uint8_t* p) {
  return uint32_t{p[0]} << 8 | p[1];
}
uint32_t le16(const uint8_t* p) {
  return uint32_t{p[0]} | uint32_t{p[1]} << 8;
}
uint32_t le24(const uint8_t* p) {
  return uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16;
}
uint32_t le32(const uint8_t* p) {
  return le24(p) | uint32_t{p[3]} << 24;
}

[[noreturn]] void fail(const std::string& what) {
  throw FormatError("8", "image tile: " + what);
}

ImageHeader png(std::span<const uint8_t> b) {
  // Signature, then the IHDR chunk: length 13, "IHDR", width, height, depth, colour type.
  if (b.size() < 8 + 8 + 13 + 4) fail("PNG truncated before the end of IHDR");
  if (be32(b.data() + 8) != 13 || std::memcmp(b.data() + 12, "IHDR", 4) != 0)
    fail("PNG does not start with an IHDR chunk");
  ImageHeader h;
  h.format = ImageFormat::kPng;
  const uint32_t w = be32(b.data() + 16), ht = be32(b.data() + 20);
  if (w == 0 || ht == 0 || w > 0x7fffffff || ht > 0x7fffffff) fail("PNG has invalid dimensions");
  h.width = static_cast<int>(w);
  h.height = static_cast<int>(ht);
  switch (b[25]) {
    case 0:
      h.channels = 1;
      break;
    case 2:
      h.channels = 3;
      break;
    case 3:
      h.channels = 3;
      break;  // palette
    case 4:
      h.channels = 2;
      break;
    case 6:
      h.channels = 4;
      break;
    default:
      fail("PNG has an unknown colour type " + std::to_string(b[25]));
  }
  return h;
}

ImageHeader jpeg(std::span<const uint8_t> b) {
  // Markers after SOI; the first start-of-frame (SOF0..SOF15 except DHT,
  // JPG and DAC) gives the size and component count.
  size_t i = 2;
  while (true) {
    if (i + 4 > b.size()) fail("JPEG truncated before its frame header");
    if (b[i] != 0xFF) fail("JPEG marker expected at byte " + std::to_string(i));
    const uint8_t marker = b[i + 1];
    if (marker == 0xFF) {  // fill byte
      ++i;
      continue;
    }
    if (marker == 0xD8 || (marker >= 0xD0 && marker <= 0xD7) || marker == 0x01) {
      i += 2;
      continue;
    }
    if (marker == 0xD9 || marker == 0xDA) fail("JPEG has no frame header before its scan");
    const uint32_t len = be16(b.data() + i + 2);
    if (len < 2) fail("JPEG segment length below 2");
    if (marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC) {
      if (len < 8 || i + 2 + len > b.size()) fail("JPEG frame header truncated");
      ImageHeader h;
      h.format = ImageFormat::kJpeg;
      h.height = static_cast<int>(be16(b.data() + i + 5));
      h.width = static_cast<int>(be16(b.data() + i + 7));
      h.channels = b[i + 9];
      if (h.width == 0 || h.height == 0) fail("JPEG has zero dimensions");
      if (h.channels != 1 && h.channels != 3)
        fail("JPEG has " + std::to_string(h.channels) + " components (1 or 3 expected)");
      return h;
    }
    i += 2 + len;
  }
}

ImageHeader webp(std::span<const uint8_t> b) {
  // RIFF container: "RIFF" size "WEBP", then a VP8, VP8L or VP8X chunk.
  if (b.size() < 30) fail("WebP truncated before its first chunk's header");
  if (uint64_t{le32(b.data() + 4)} + 8 > b.size()) fail("WebP RIFF size exceeds the blob");
  const uint8_t* c = b.data() + 12;
  ImageHeader h;
  h.format = ImageFormat::kWebp;
  if (std::memcmp(c, "VP8 ", 4) == 0) {
    if (c[11] != 0x9d || c[12] != 0x01 || c[13] != 0x2a) fail("WebP VP8 frame without start code");
    h.width = static_cast<int>(le16(c + 14) & 0x3fff);
    h.height = static_cast<int>(le16(c + 16) & 0x3fff);
    h.channels = 3;
  } else if (std::memcmp(c, "VP8L", 4) == 0) {
    if (c[8] != 0x2f) fail("WebP VP8L chunk without signature");
    const uint32_t bits = le32(c + 9);
    h.width = static_cast<int>((bits & 0x3fff) + 1);
    h.height = static_cast<int>(((bits >> 14) & 0x3fff) + 1);
    h.channels = (bits >> 28) & 1 ? 4 : 3;
  } else if (std::memcmp(c, "VP8X", 4) == 0) {
    h.width = static_cast<int>(le24(c + 12) + 1);
    h.height = static_cast<int>(le24(c + 15) + 1);
    h.channels = c[8] & 0x10 ? 4 : 3;
  } else {
    fail("WebP first chunk is not VP8, VP8L or VP8X");
  }
  if (h.width == 0 || h.height == 0) fail("WebP has zero dimensions");
  return h;
}

}  // namespace

ImageHeader inspect_image_tile(std::span<const uint8_t> b) {
  static const uint8_t kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (b.size() >= 8 && std::memcmp(b.data(), kPng, 8) == 0) return png(b);
  if (b.size() >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) return jpeg(b);
  if (b.size() >= 12 && std::memcmp(b.data(), "RIFF", 4) == 0 &&
      std::memcmp(b.data() + 8, "WEBP", 4) == 0)
    return webp(b);
  fail("not a PNG, JPEG or WebP file (" + std::to_string(b.size()) + " bytes)");
}

const char* image_format_name(ImageFormat f) {
  switch (f) {
    case ImageFormat::kPng:
      return "png";
    case ImageFormat::kJpeg:
      return "jpg";
    case ImageFormat::kWebp:
      return "webp";
  }
  return "?";
}

std::optional<ImageFormat> parse_image_format(const std::string& name) {
  if (name == "png") return ImageFormat::kPng;
  if (name == "jpg" || name == "jpeg") return ImageFormat::kJpeg;
  if (name == "webp") return ImageFormat::kWebp;
  return std::nullopt;
}

}  // namespace tileformat
