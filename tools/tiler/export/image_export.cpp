// Image package export (see image_export.hpp).
#include "export/image_export.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <vector>

#include "runtime/errors.hpp"
#include "runtime/image_package.hpp"
#include "tileformat/pmtiles.hpp"
#include "web/tile_output.hpp"

namespace globe {

ExportSummary export_images(const ImageExportSettings& s, Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  ImagePackage pkg = open_image_package(s.input);
  if (pkg.tiling.scheme != tileformat::Scheme::kWebMercator)
    throw UsageError(s.input + ": web maps read web mercator tiles and this package is in the " +
                     tileformat::scheme_name(pkg.tiling.scheme) +
                     " tiling; build it with --tiling webmercator");
  namespace pm = tileformat::pmtiles;
  const std::vector<tileformat::TileId> items =
      tiles_in_output_order(pkg.file(), pkg.min_zoom, pkg.max_zoom);

  ExportInfo info;
  switch (pkg.format) {
    case tileformat::ImageFormat::kJpeg:
      info.format = info.extension = "jpg", info.tile_type = pm::TileType::kJpeg;
      break;
    case tileformat::ImageFormat::kWebp:
      info.format = info.extension = "webp", info.tile_type = pm::TileType::kWebp;
      break;
    default:
      info.format = info.extension = "png", info.tile_type = pm::TileType::kPng;
  }
  std::unique_ptr<TileOutput> out = TileOutput::open(s.output, s.force, info.extension, false);
  progress.begin("copy tiles", items.size());
  for (const tileformat::TileId& it : items) {
    const auto blob = pkg.reader->tile(it);
    if (blob) out->put(it.z, it.x, it.y, *blob);
    progress.advance();
  }
  progress.end();
  const tileformat::Bounds& b = pkg.meta.common.lonlat;
  info.name = std::filesystem::path(s.output).stem().string();
  info.description = "Tiles of " + s.input + " (" + pkg.meta.common.description + ")";
  info.min_zoom = pkg.min_zoom, info.max_zoom = pkg.max_zoom;
  info.west = b.min_x, info.south = b.min_y, info.east = b.max_x, info.north = b.max_y;
  info.extra_json = "\"tileSize\":" + std::to_string(pkg.tile_size);
  ExportSummary sum;
  sum.tiles = out->tiles();
  sum.bytes = out->finish(info);
  sum.min_zoom = pkg.min_zoom, sum.max_zoom = pkg.max_zoom;
  sum.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sum;
}

}  // namespace globe
