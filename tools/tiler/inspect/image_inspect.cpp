// `globe-tiler info`, `validate` and `extract` for image packages. extract
// writes the tile pixels of one zoom as a Byte GeoTIFF (gray or RGB, then
// alpha). validate checks (docs/tileformat.md §3, §8):
//   - MBTiles 1.3 metadata present;
//   - every tile inside the tiling and the zoom range, a PNG/JPEG/WebP of
//     tile_size x tile_size pixels that decodes, in the package's format
//     (PNG allowed in jpg packages for tiles with transparent pixels);
//   - no fully transparent tile (empty tiles are not written);
//   - png packages built by globe-tiler: every parent equals the alpha-
//     weighted 2 x 2 average of its children (the pyramid rule), exactly.
// Report on stdout. Exit 0 valid, 5 warnings only, 1 errors.
#include <gdal.h>

#include <cstdio>
#include <map>
#include <optional>

#include "geo/gdal_dataset.hpp"
#include "geo/image_codec.hpp"
#include "imagery/image_pyramid.hpp"
#include "inspect/inspect_commands.hpp"
#include "kit/package_info.hpp"
#include "kit/validation_report.hpp"
#include "runtime/errors.hpp"
#include "runtime/image_package.hpp"
#include "tileformat/error.hpp"

namespace globe {
namespace {

int validate_image(const std::string& path) {
  using tileformat::ImageFormat;
  using tileformat::TileId;
  ImagePackage p = open_image_package(path);
  ValidationReport r;
  const bool ours = p.reader->meta("globe:scheme").has_value();
  if (ours && p.file().application_id() != tileformat::kApplicationId)
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
  p.file().for_each_tile([&](TileId id, std::span<const uint8_t>) { ids.push_back(id); });
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

int image_info(const std::string& path, bool json) {
  ImagePackage p = open_image_package(path);
  uint64_t counts[3] = {0, 0, 0}, bad = 0;
  p.file().for_each_tile([&](tileformat::TileId, std::span<const uint8_t> blob) {
    try {
      ++counts[static_cast<int>(tileformat::inspect_image_tile(blob).format)];
    } catch (const tileformat::FormatError&) {
      ++bad;
    }
  });
  if (json) {
    InfoJson image;
    image.integer("tile_px", uint64_t(p.tile_size))
        .text("colour", p.colour == 1 ? "gray" : "rgb")
        .object("stored", InfoJson()
                              .integer("png", counts[0])
                              .integer("jpg", counts[1])
                              .integer("webp", counts[2]))
        .integer("not_images", bad);
    print_kind_info_json(p.file(), path, tileformat::PackageKind::kImage, image);
    return kExitOk;
  }
  print_package_info(p.file(), path);
  std::printf("image: %d x %d px tiles, %s + alpha; tiles stored as png %llu, jpg %llu, webp %llu",
              p.tile_size, p.tile_size, p.colour == 1 ? "gray" : "RGB",
              static_cast<unsigned long long>(counts[0]),
              static_cast<unsigned long long>(counts[1]),
              static_cast<unsigned long long>(counts[2]));
  if (bad) std::printf(", not an image %llu (run validate)", static_cast<unsigned long long>(bad));
  std::printf("\n");
  return kExitOk;
}

int extract_image(const ExtractRequest& rq) {
  if (!rq.layer.empty()) throw UsageError("--layer applies to analysis packages only");
  const std::string& path = rq.package;
  ImagePackage p = open_image_package(path);
  const ExtractTiles t = tiles_to_extract(p.file(), p.tiling, rq, p.min_zoom, p.max_zoom);
  const auto& ids = t.ids;
  const uint32_t x0 = t.x0, y0 = t.y0;
  const int n = p.tile_size;
  const uint64_t w = uint64_t(t.cols) * n, h = uint64_t(t.rows) * n;
  if (w > 200000 || h > 200000)
    throw UsageError("the extract would be " + std::to_string(w) + " x " + std::to_string(h) +
                     " pixels; limit it with --bbox");
  const double px = p.tiling.sample_spacing(rq.zoom, n);
  const auto corner = p.tiling.tile_bounds({rq.zoom, x0, y0});
  const std::array<double, 6> gt{corner.min_x, px, 0, corner.max_y, 0, -px};
  const int bands = p.colour + 1;
  ExtractTiff out(rq, static_cast<int>(w), static_cast<int>(h), bands, GDT_Byte, gt, p.tiling.crs);
  const GDALColorInterp colours[] = {GCI_RedBand, GCI_GreenBand, GCI_BlueBand};
  for (int b = 1; b <= p.colour; ++b)
    out.dataset().set_colour(b, p.colour == 1 ? GCI_GrayIndex : colours[b - 1]);
  out.dataset().set_colour(bands, GCI_AlphaBand);
  for (const auto& id : ids) {
    TilePixels tile;
    try {
      tile = decode_image_tile(*p.reader->tile(id), n, p.colour);
    } catch (const tileformat::FormatError& e) {
      throw InputError(path + ": tile " + id.str() + ": " + e.what());
    }
    for (int b = 0; b < bands; ++b)
      out.dataset().write(b + 1, int(id.x - x0) * n, int(id.y - y0) * n, n, n, tile.plane(b),
                          GDT_Byte);
  }
  out.commit();
  std::fprintf(stderr, "globe-tiler: wrote %s: %llu x %llu pixels from %zu tiles of zoom %d\n",
               rq.output.c_str(), static_cast<unsigned long long>(w),
               static_cast<unsigned long long>(h), ids.size(), rq.zoom);
  return kExitOk;
}

}  // namespace

// This kind's row of the tool's table (inspect/inspect_commands.cpp).
extern const KindInspection kImageInspection{tileformat::PackageKind::kImage, image_info,
                                             validate_image, extract_image};

}  // namespace globe
