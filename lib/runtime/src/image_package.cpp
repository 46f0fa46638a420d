// Opening image packages (see image_package.hpp).
#include "runtime/image_package.hpp"

#include "runtime/errors.hpp"
#include "runtime/package_open.hpp"
#include "tileformat/error.hpp"

namespace globe {

ImagePackage open_image_package(const std::string& path) {
  ImagePackage p;
  p.reader = open_package_of_kind(path, tileformat::PackageKind::kImage);
  p.meta =
      read_metadata(path, [&] { return tileformat::read_image_metadata(p.reader->metadata()); });
  p.format = p.meta.format;
  p.tiling = p.meta.common.tiling;
  p.min_zoom = p.meta.common.min_zoom;
  p.max_zoom = p.meta.common.max_zoom;
  p.tile_size = p.meta.tile_size;
  p.colour = p.meta.colour_bands;
  if (p.meta.common.has_tiling) return p;
  // Another tool's MBTiles: the first tile that decodes says.
  p.tile_size = 256;
  p.colour = 3;
  bool found = false;
  p.file().for_each_tile([&](tileformat::TileId, std::span<const uint8_t> blob) {
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
