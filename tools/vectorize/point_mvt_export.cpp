// Point packages to Mapbox Vector Tiles (see point_mvt_export.hpp).
#include "point_mvt_export.hpp"

#include <chrono>
#include <filesystem>

#include "errors.hpp"
#include "gzip.hpp"
#include "mvt_encoder.hpp"
#include "point_mvt.hpp"
#include "point_package.hpp"
#include "tile_output.hpp"
#include "tileformat/error.hpp"
#include "tileformat/json.hpp"
#include "tileformat/pmtiles.hpp"
#include "tileformat/point_tile.hpp"

namespace globe {

MvtExportSummary export_point_mvt(const MvtExportSettings& s, Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  PointPackage pkg = open_point_package(s.input);
  const tileformat::CommonMetadata& common = pkg.meta.common;
  if (common.tiling.scheme != tileformat::Scheme::kWebMercator)
    throw UsageError(s.input +
                     ": web maps read web mercator vector tiles and this package is in the " +
                     std::string(tileformat::scheme_name(common.tiling.scheme)) +
                     " tiling; build it with --tiling webmercator");
  const std::vector<tileformat::TileId> items =
      tiles_in_output_order(*pkg.reader, common.min_zoom, common.max_zoom);
  std::unique_ptr<TileOutput> out = TileOutput::open(s.output, s.force, "pbf", false);
  MvtExportSummary sum;
  progress.begin("encode vector tiles", items.size());
  for (const tileformat::TileId& it : items) {
    const auto blob = pkg.reader->tile(it);
    progress.advance();
    if (!blob) continue;
    const std::vector<uint8_t> tile = web::point_tile_mvt(pkg, it, *blob, &sum.features);
    if (!tile.empty()) out->put(it.z, it.x, it.y, web::gzip(tile));
  }
  progress.end();

  ExportInfo info;
  info.name = std::filesystem::path(s.output).stem().string();
  info.description = "Places of " + s.input + " as Mapbox Vector Tiles 2.1 (gzip); values are " +
                     (pkg.meta.aggregate == tileformat::PointAggregate::kMean ? "means" : "sums") +
                     " over the places each stands for";
  info.format = "pbf";
  info.extension = "pbf";
  info.type = "overlay";
  info.tile_type = tileformat::pmtiles::TileType::kMvt;
  info.tile_compression = tileformat::pmtiles::Compression::kGzip;
  info.min_zoom = common.min_zoom, info.max_zoom = common.max_zoom;
  const tileformat::Bounds& b = common.lonlat;
  info.west = b.min_x, info.south = b.min_y, info.east = b.max_x, info.north = b.max_y;
  info.extra_json = "\"vector_layers\":" + web::vector_layers_json(web::point_mvt_fields(pkg));
  sum.tiles = out->tiles();
  sum.bytes = out->finish(info);
  if (!s.style_json.empty())
    write_style_json(s.style_json, web::point_style_json(pkg, mvt_source_url(s.output)));
  sum.min_zoom = common.min_zoom, sum.max_zoom = common.max_zoom;
  sum.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sum;
}

}  // namespace globe
