// Point tiles as Mapbox Vector Tiles (see point_mvt.hpp).
#include "web/point_mvt.hpp"

#include "runtime/errors.hpp"
#include "tileformat/error.hpp"
#include "tileformat/json.hpp"
#include "tileformat/point_tile.hpp"
#include "web/mvt_encoder.hpp"

namespace globe::web {

std::vector<uint8_t> point_tile_mvt(const PointPackage& package, tileformat::TileId id,
                                    std::span<const uint8_t> blob, uint64_t* places,
                                    const MvtLabels* labels) {
  tileformat::PointTile t;
  try {
    t = tileformat::decode_point_tile(blob);
  } catch (const tileformat::FormatError& e) {
    throw InputError(package.reader->path() + ": tile " + id.str() + ": " + e.what() +
                     "; check the package with globe-vectorize validate");
  }
  std::vector<MvtLayer> layers;
  layers.emplace_back("points", t.extent);
  const std::vector<std::string>& names = package.meta.fields;
  for (size_t p = 0; p < t.places.size(); ++p) {
    const tileformat::Place& place = t.places[p];
    std::vector<std::pair<std::string, MvtValue>> tags;
    MvtValue count;
    count.kind = MvtValue::Kind::kInt;
    count.integer = place.count;
    tags.emplace_back("count", count);
    for (uint32_t f = 0; f < t.fields && f < names.size(); ++f) {
      MvtValue v;
      v.kind = MvtValue::Kind::kDouble;
      v.number = t.value(p, f);
      tags.emplace_back(names[f], v);
    }
    if (labels && place.count == 1)
      if (const std::string* name = labels->text(place.id)) set_name_tag(tags, *name);
    layers[0].add_point(place.id, {place.at.x, place.at.y}, tags);
  }
  if (places) *places += t.places.size();
  return encode_mvt(layers);
}

std::map<std::string, std::map<std::string, std::string>> point_mvt_fields(
    const PointPackage& package, const MvtLabels* labels) {
  std::map<std::string, std::string> fields{{"count", "Number"}};
  for (const std::string& f : package.meta.fields)
    fields[f] = "Number";
  if (labels && !labels->empty()) fields["name"] = "String";
  return {{"points", fields}};
}

// Circles whose area follows the count (radius by its square root), white
// rim; the names beside the circles, on whichever side they fit.
std::string point_style_json(const PointPackage& package, const std::string& source_url,
                             const StyleGlyphs& glyphs) {
  const std::string names =
      glyphs.empty()
          ? std::string()
          : "," + label_layer_json("points:labels", "points", "points", glyphs,
                                   ",\"text-variable-anchor\":[\"left\",\"right\",\"top\","
                                   "\"bottom\"],\"text-radial-offset\":0.6,"
                                   "\"text-justify\":\"auto\"");
  return "{\"version\":8,\"name\":\"" + tileformat::json_escape(package.meta.common.name) + "\"" +
         style_glyphs_member(glyphs) + ",\"sources\":{\"points\":{\"type\":\"vector\",\"url\":\"" +
         tileformat::json_escape(source_url) +
         "\"}},\"layers\":[{\"id\":\"points\",\"type\":\"circle\",\"source\":\"points\","
         "\"source-layer\":\"points\",\"paint\":{\"circle-color\":\"#d7301f\","
         "\"circle-opacity\":0.8,\"circle-stroke-color\":\"#ffffff\",\"circle-stroke-width\":1,"
         "\"circle-radius\":[\"interpolate\",[\"linear\"],[\"sqrt\",[\"get\",\"count\"]],1,3,"
         "100,30]}}" +
         names + "]}";
}

}  // namespace globe::web
