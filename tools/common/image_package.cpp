// Opening image packages (see image_package.hpp).
#include "image_package.hpp"

#include "errors.hpp"
#include "package_open.hpp"
#include "tileformat/error.hpp"

namespace globe {

bool is_image_format(const std::string& format) {
  return format == "png" || format == "jpg" || format == "webp";
}

ImagePackage open_image_package(const std::string& path) {
  ImagePackage p;
  p.reader = open_package(path);
  const std::string fmt = package_format(*p.reader, path);
  if (!is_image_format(fmt))
    throw InputError(path + ": a '" + fmt + "' package, not an image package (png, jpg, webp)");
  p.format = *tileformat::parse_image_format(fmt);
  const bool ours = p.reader->meta("globe:scheme").has_value();
  p.tiling = ours ? meta_tiling(*p.reader, path) : tileformat::Tiling::webmercator();
  p.min_zoom = static_cast<int>(meta_number(*p.reader, path, "minzoom"));
  p.max_zoom = static_cast<int>(meta_number(*p.reader, path, "maxzoom"));
  if (ours) {
    p.tile_size = static_cast<int>(meta_number(*p.reader, path, "globe:tile_size"));
    p.colour = static_cast<int>(meta_number(*p.reader, path, "globe:colour_bands"));
    if ((p.tile_size != 256 && p.tile_size != 512) || (p.colour != 1 && p.colour != 3))
      throw InputError(path +
                       ": globe:tile_size must be 256 or 512 and globe:colour_bands 1 or 3 "
                       "(tileformat §8)");
    return p;
  }
  bool found = false;
  p.reader->for_each_tile([&](tileformat::TileId, std::span<const uint8_t> blob) {
    if (found) return;
    try {
      const auto h = tileformat::inspect_image_tile(blob);
      p.tile_size = h.width;
      p.colour = h.channels >= 3 ? 3 : 1;
      found = true;
    } catch (const tileformat::FormatError&) {
    }
  });
  return p;
}

}  // namespace globe
