// Point packages to Mapbox Vector Tiles (see point_mvt_export.hpp).
#include "point_mvt_export.hpp"

#include <chrono>
#include <filesystem>
#include <map>

#include "errors.hpp"
#include "gzip.hpp"
#include "mvt_encoder.hpp"
#include "point_package.hpp"
#include "tile_output.hpp"
#include "tileformat/error.hpp"
#include "tileformat/json.hpp"
#include "tileformat/pmtiles.hpp"
#include "tileformat/point_tile.hpp"

namespace globe {
namespace {

// Circles whose area follows the count (radius by its square root), in the
// viewer's first chart colour, white rim.
std::string point_style(const PointPackage& pkg, const std::string& source_url) {
  return "{\"version\":8,\"name\":\"" + tileformat::json_escape(pkg.meta.common.name) +
         "\",\"sources\":{\"points\":{\"type\":\"vector\",\"url\":\"" +
         tileformat::json_escape(source_url) +
         "\"}},\"layers\":[{\"id\":\"points\",\"type\":\"circle\",\"source\":\"points\","
         "\"source-layer\":\"points\",\"paint\":{\"circle-color\":\"#d7301f\","
         "\"circle-opacity\":0.8,\"circle-stroke-color\":\"#ffffff\",\"circle-stroke-width\":1,"
         "\"circle-radius\":[\"interpolate\",[\"linear\"],[\"sqrt\",[\"get\",\"count\"]],1,3,"
         "100,30]}}]}";
}

}  // namespace

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
    tileformat::PointTile t;
    try {
      t = tileformat::decode_point_tile(*blob);
    } catch (const tileformat::FormatError& e) {
      throw InputError(s.input + ": tile " + it.str() + ": " + e.what() +
                       "; check the package with globe-vectorize validate");
    }
    std::vector<web::MvtLayer> layers;
    layers.emplace_back("points", t.extent);
    for (size_t p = 0; p < t.places.size(); ++p) {
      const tileformat::Place& place = t.places[p];
      std::vector<std::pair<std::string, web::MvtValue>> tags;
      web::MvtValue count;
      count.kind = web::MvtValue::Kind::kInt;
      count.integer = place.count;
      tags.emplace_back("count", count);
      for (uint32_t f = 0; f < t.fields && f < pkg.meta.fields.size(); ++f) {
        web::MvtValue v;
        v.kind = web::MvtValue::Kind::kDouble;
        v.number = t.value(p, f);
        tags.emplace_back(pkg.meta.fields[f], v);
      }
      layers[0].add_point(place.id, {place.at.x, place.at.y}, tags);
      ++sum.features;
    }
    const std::vector<uint8_t> tile = web::encode_mvt(layers);
    if (!tile.empty()) out->put(it.z, it.x, it.y, web::gzip(tile));
  }
  progress.end();

  std::map<std::string, std::string> fields{{"count", "Number"}};
  for (const std::string& f : pkg.meta.fields)
    fields[f] = "Number";
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
  info.extra_json = "\"vector_layers\":" + web::vector_layers_json({{"points", fields}});
  sum.tiles = out->tiles();
  sum.bytes = out->finish(info);
  if (!s.style_json.empty())
    write_style_json(s.style_json, point_style(pkg, mvt_source_url(s.output)));
  sum.min_zoom = common.min_zoom, sum.max_zoom = common.max_zoom;
  sum.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sum;
}

}  // namespace globe
