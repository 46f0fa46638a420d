// `globe-tiler validate` for image packages (docs/tileformat.md §3, §8):
//   - MBTiles 1.3 metadata present;
//   - every tile inside the tiling and the zoom range, a PNG/JPEG/WebP of
//     tile_size x tile_size pixels that decodes, in the package's format
//     (PNG allowed in jpg packages for tiles with transparent pixels);
//   - no fully transparent tile (empty tiles are not written);
//   - png packages built by globe-tiler: every parent equals the alpha-
//     weighted 2 x 2 average of its children (the pyramid rule), exactly.
// Report on stdout. Exit 0 valid, 5 warnings only, 1 errors.
#include <cstdio>
#include <map>
#include <optional>

#include "geo/image_codec.hpp"
#include "imagery/image_pyramid.hpp"
#include "inspect/inspect_commands.hpp"
#include "kit/validation_report.hpp"
#include "runtime/image_package.hpp"
#include "tileformat/error.hpp"

namespace globe {

int validate_image_package(const std::string& path) {
  using tileformat::ImageFormat;
  using tileformat::TileId;
  ImagePackage p = open_image_package(path);
  ValidationReport r;
  const bool ours = p.reader->meta("globe:scheme").has_value();
  if (ours && p.reader->application_id() != tileformat::kApplicationId)
    r.warning("PRAGMA application_id is not 0x4d504258 (tileformat §3.1)");
  for (const char* key :
       {"name", "bounds", "center", "minzoom", "maxzoom", "type", "version", "description"})
    if (!p.reader->meta(key))
      r.warning(std::string("metadata key '") + key +
                "' is missing (MBTiles 1.3, tileformat §3.2)");
  if (ours)
    for (const char* key : {"globe:format_version", "globe:command_line"})
      if (!p.reader->meta(key))
        r.warning(std::string("metadata key '") + key + "' is missing (tileformat §3.2)");

  std::vector<TileId> ids;
  p.reader->for_each_tile([&](TileId id, std::span<const uint8_t>) { ids.push_back(id); });
  std::map<TileId, bool> present;
  for (const TileId& id : ids)
    present[id] = true;
  auto decode = [&](TileId id) -> std::optional<TilePixels> {
    try {
      return decode_image_tile(*p.reader->tile(id), p.tile_size, p.colour);
    } catch (const tileformat::FormatError&) {
      return std::nullopt;  // reported when the tile itself is checked
    }
  };
  const bool check_pyramid = ours && p.format == ImageFormat::kPng;
  for (const TileId& id : ids) {
    const std::string where = "tile " + id.str();
    if (!p.tiling.contains(id)) {
      r.error(where + ": outside the tiling's extent");
      continue;
    }
    if (id.z < p.min_zoom || id.z > p.max_zoom) r.error(where + ": zoom outside minzoom..maxzoom");
    const std::vector<uint8_t> blob = *p.reader->tile(id);
    TilePixels px;
    try {
      const auto header = tileformat::inspect_image_tile(blob);
      px = decode_image_tile(blob, p.tile_size, p.colour);
      if (header.format != p.format &&
          !(p.format == ImageFormat::kJpeg && header.format == ImageFormat::kPng))
        r.error(where + ": a " + tileformat::image_format_name(header.format) + " tile in a " +
                tileformat::image_format_name(p.format) + " package (tileformat §8)");
      else if (header.format != p.format && px.opaque())
        r.warning(where + ": an opaque PNG tile in a jpg package (tileformat §8)");
    } catch (const tileformat::FormatError& e) {
      r.error(where + ": " + e.what());
      continue;
    }
    if (px.empty()) r.warning(where + ": every pixel is transparent (tileformat §8)");
    if (!check_pyramid || id.z == p.max_zoom) continue;
    std::array<std::optional<TilePixels>, 4> kids;
    std::array<const TilePixels*, 4> ptrs{};
    bool complete = true;
    const auto children = id.children();
    for (int c = 0; c < 4; ++c) {
      if (!present.count(children[c])) continue;
      kids[c] = decode(children[c]);
      if (!kids[c]) complete = false;
      ptrs[c] = kids[c] ? &*kids[c] : nullptr;
    }
    if (complete && downsample_children(ptrs, p.tile_size, p.colour).planes != px.planes)
      r.error(where + ": pixels differ from the average of its children (tileformat §8)");
  }
  std::printf("%s: %zu tiles checked, %llu errors, %llu warnings\n", path.c_str(), ids.size(),
              static_cast<unsigned long long>(r.errors),
              static_cast<unsigned long long>(r.warnings));
  return r.exit_code();
}

}  // namespace globe
