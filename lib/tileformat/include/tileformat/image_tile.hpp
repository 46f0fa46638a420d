// Image tiles (docs/tileformat.md §8): the blobs of an image package are
// plain PNG, JPEG or WebP files, so GDAL, QGIS and web maps read them as
// MBTiles. This identifies a blob and reads its dimensions from the header
// alone (bounds-checked, no pixel decoding); decoding pixels is left to the
// image libraries (tools decode through GDAL).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace tileformat {

enum class ImageFormat { kPng, kJpeg, kWebp };

struct ImageHeader {
  ImageFormat format = ImageFormat::kPng;
  int width = 0, height = 0;
  int channels = 0;  // 1 gray, 2 gray+alpha, 3 RGB, 4 RGBA (0: not in the header)
};

// Throws FormatError(§8) if the blob is not a PNG, JPEG or WebP whose header
// gives positive dimensions.
ImageHeader inspect_image_tile(std::span<const uint8_t> blob);

// "png", "jpg", "webp": the MBTiles `format` values.
const char* image_format_name(ImageFormat f);
// From a `format` value or a --format argument ("jpeg" = "jpg"); nullopt if unknown.
std::optional<ImageFormat> parse_image_format(const std::string& name);

}  // namespace tileformat
