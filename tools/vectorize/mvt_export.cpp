// Line packages to Mapbox Vector Tiles (see mvt_export.hpp).
#include "mvt_export.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <unordered_map>

#include "errors.hpp"
#include "gzip.hpp"
#include "line_package.hpp"
#include "mvt_encoder.hpp"
#include "tile_output.hpp"
#include "tileformat/error.hpp"
#include "tileformat/feature_table.hpp"
#include "tileformat/json.hpp"
#include "tileformat/line_tile.hpp"
#include "tileformat/pmtiles.hpp"

namespace globe {
namespace {

namespace pm = tileformat::pmtiles;
using Tags = std::vector<std::pair<std::string, web::MvtValue>>;

web::MvtValue value_of(const tileformat::JsonValue& v) {
  web::MvtValue m;
  if (v.is_number()) {
    const double d = v.number();
    if (d == std::floor(d) && std::fabs(d) < 9e15) {
      m.kind = web::MvtValue::Kind::kInt;
      m.integer = static_cast<int64_t>(d);
    } else {
      m.kind = web::MvtValue::Kind::kDouble;
      m.number = d;
    }
  } else if (v.is_bool()) {
    m.kind = web::MvtValue::Kind::kBool;
    m.flag = v.boolean();
  } else if (v.is_string()) {
    m.text = v.string();
  } else {
    m.text = v.text();  // arrays and objects as JSON text
  }
  return m;
}

// A feature's MVT layer and tags, read once from the features table.
struct FeatureInfo {
  std::string layer;
  Tags tags;
};

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// A MapLibre style (version 8) drawing the classes as the viewer does:
// casings under fills, class ids in order (higher on top).
std::string maplibre_style(const LinePackage& pkg,
                           const std::map<std::string, std::set<uint32_t>>& classes_in,
                           const std::string& source_url) {
  std::string out = "{\"version\":8,\"name\":\"" + tileformat::json_escape(pkg.meta.common.name) +
                    "\",\"sources\":{\"lines\":{\"type\":\"vector\",\"url\":\"" +
                    tileformat::json_escape(source_url) + "\"}},\"layers\":[";
  bool first = true;
  auto width = [](const LineStyle& s, double w) {
    if (!s.width_in_m) return number(w);
    // Metres to pixels at the equator, doubling each zoom (web mercator z0:
    // 156543.03 m per pixel of a 256-pixel tile).
    return "[\"interpolate\",[\"exponential\",2],[\"zoom\"],0," + number(w / 156543.03) + ",24," +
           number(w / 156543.03 * 16777216.0) + "]";
  };
  for (int pass = 0; pass < 2; ++pass)
    for (size_t c = 0; c < pkg.classes.size(); ++c) {
      const LineStyle& s = pkg.classes[c].style;
      const bool casing = !s.casing_color.empty() && s.casing_width > 0;
      if (!s.visible || (pass == 0 && !casing)) continue;
      for (const auto& [layer, classes] : classes_in) {
        if (!classes.count(uint32_t(c))) continue;
        out += first ? "" : ",";
        first = false;
        const std::string id = layer + "/" + pkg.classes[c].name + (pass == 0 ? "/casing" : "");
        out += "{\"id\":\"" + tileformat::json_escape(id) +
               "\",\"type\":\"line\",\"source\":\"lines\",\"source-layer\":\"" +
               tileformat::json_escape(layer) + "\",\"filter\":[\"==\",[\"get\",\"class\"],\"" +
               tileformat::json_escape(pkg.classes[c].name) +
               "\"],\"layout\":{\"line-cap\":\"round\",\"line-join\":\"round\"},\"paint\":{";
        if (pass == 0) {
          out += "\"line-color\":\"" + s.casing_color +
                 "\",\"line-width\":" + width(s, s.width + 2 * s.casing_width);
        } else {
          out += "\"line-color\":\"" + s.color + "\",\"line-width\":" + width(s, s.width);
          if (!s.dash.empty()) {
            out += ",\"line-dasharray\":[";
            for (size_t k = 0; k < s.dash.size(); ++k)
              out += (k ? "," : "") + number(s.dash[k] / std::max(s.width, 1e-9));
            out += "]";
          }
        }
        out += ",\"line-opacity\":" + number(s.opacity) + "}}";
      }
    }
  return out + "]}";
}

}  // namespace

std::string mvt_source_url(const std::string& output) {
  const std::string name = std::filesystem::path(output).filename().string();
  switch (output_kind(output)) {
    case OutputKind::kPmtiles:
      return "pmtiles://" + name;
    case OutputKind::kDirectory:
      return name + "/metadata.json";
    default:
      return name;
  }
}

void write_style_json(const std::string& path, const std::string& style) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << style << "\n";
    if (!out) throw OutputError(tmp + ": cannot write (disk full?)");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw OutputError(path + ": cannot write (" + ec.message() + ")");
}

MvtExportSummary export_mvt(const MvtExportSettings& s, Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  LinePackage pkg = open_line_package(s.input);
  if (pkg.tiling.scheme != tileformat::Scheme::kWebMercator)
    throw UsageError(s.input +
                     ": web maps read web mercator vector tiles and this package is in "
                     "the " +
                     std::string(tileformat::scheme_name(pkg.tiling.scheme)) +
                     " tiling; build it with --tiling webmercator");
  std::unique_ptr<tileformat::FeatureTableReader> table;
  try {
    table = std::make_unique<tileformat::FeatureTableReader>(*pkg.reader);
  } catch (const tileformat::FormatError&) {
    table.reset();  // an older package: ids and classes only
  }
  const std::vector<tileformat::TileId> items =
      tiles_in_output_order(*pkg.reader, pkg.min_zoom, pkg.max_zoom);

  std::unique_ptr<TileOutput> out = TileOutput::open(s.output, s.force, "pbf", false);
  std::unordered_map<uint64_t, FeatureInfo> features;  // cleared when large
  auto feature = [&](uint64_t id) -> const FeatureInfo& {
    if (auto it = features.find(id); it != features.end()) return it->second;
    if (features.size() > 200000) features.clear();
    FeatureInfo info{"lines", {}};
    if (table)
      if (const auto rec = table->get(int64_t(id))) {
        info.layer = rec->layer.empty() ? "lines" : rec->layer;
        try {
          const tileformat::JsonValue props = tileformat::JsonValue::parse(rec->properties);
          if (props.is_object())
            for (const auto& [k, v] : props.members())
              if (k != "class") info.tags.emplace_back(k, value_of(v));
        } catch (const tileformat::JsonError&) {
          // attributes that are not JSON: the feature keeps its id and class
        }
      }
    return features.emplace(id, std::move(info)).first->second;
  };
  MvtExportSummary sum;
  std::map<std::string, std::set<uint32_t>> classes_in;              // MVT layer -> classes drawn
  std::map<std::string, std::map<std::string, std::string>> fields;  // layer -> key -> type
  progress.begin("encode vector tiles", items.size());
  for (const tileformat::TileId& it : items) {
    const auto blob = pkg.reader->tile(it);
    progress.advance();
    if (!blob) continue;
    tileformat::LineTile t;
    try {
      t = tileformat::decode_line_tile(*blob);
    } catch (const tileformat::FormatError& e) {
      throw InputError(s.input + ": tile " + it.str() + ": " + e.what() +
                       "; check the package with globe-vectorize validate");
    }
    std::vector<web::MvtLayer> layers;
    std::map<std::string, size_t> layer_of;
    auto layer = [&](const std::string& name, uint32_t cls) -> web::MvtLayer& {
      auto [at, fresh] = layer_of.try_emplace(name, layers.size());
      if (fresh) layers.emplace_back(name, t.extent);
      classes_in[name].insert(cls);
      return layers[at->second];
    };
    auto tags_of = [&](uint64_t id, uint32_t cls) {
      Tags tags = feature(id).tags;
      web::MvtValue c;
      c.text = cls < pkg.classes.size() ? pkg.classes[cls].name : std::to_string(cls);
      tags.insert(tags.begin(), {"class", c});
      auto& known = fields[feature(id).layer];
      for (const auto& [k, v] : tags)
        known.try_emplace(k, v.kind == web::MvtValue::Kind::kString ? "String"
                             : v.kind == web::MvtValue::Kind::kBool ? "Boolean"
                                                                    : "Number");
      return tags;
    };
    std::vector<web::MvtPoint> line;
    for (const tileformat::LineRun& r : t.runs) {
      const uint64_t id = t.feature_ids[r.feature];
      line.clear();
      for (uint32_t v = 0; v < r.vertex_count; ++v)
        line.push_back({t.vertices[r.first_vertex + v].x, t.vertices[r.first_vertex + v].y});
      ++sum.features;
      if (!layer(feature(id).layer, r.class_id).add_line(id, line, tags_of(id, r.class_id))) {
        ++sum.zero_length;
        fields[feature(id).layer]["zero_length"] = "Boolean";
      }
    }
    for (const tileformat::LinePoint& p : t.points) {
      const uint64_t id = t.feature_ids[p.feature];
      layer(feature(id).layer, p.class_id).add_point(id, {p.at.x, p.at.y}, tags_of(id, p.class_id));
      ++sum.features;
    }
    const std::vector<uint8_t> tile = web::encode_mvt(layers);
    if (!tile.empty()) out->put(it.z, it.x, it.y, web::gzip(tile));
  }
  progress.end();

  ExportInfo info;
  info.name = std::filesystem::path(s.output).stem().string();
  info.description = "Lines of " + s.input + " as Mapbox Vector Tiles 2.1 (gzip)";
  info.format = "pbf";
  info.extension = "pbf";
  info.type = "overlay";
  info.tile_type = pm::TileType::kMvt;
  info.tile_compression = pm::Compression::kGzip;
  info.min_zoom = pkg.min_zoom, info.max_zoom = pkg.max_zoom;
  const tileformat::Bounds& b = pkg.meta.common.lonlat;
  info.west = b.min_x, info.south = b.min_y, info.east = b.max_x, info.north = b.max_y;
  info.extra_json = "\"vector_layers\":" + web::vector_layers_json(fields);
  sum.tiles = out->tiles();
  sum.bytes = out->finish(info);
  if (!s.style_json.empty())
    write_style_json(s.style_json, maplibre_style(pkg, classes_in, mvt_source_url(s.output)));
  sum.min_zoom = pkg.min_zoom, sum.max_zoom = pkg.max_zoom;
  sum.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sum;
}

}  // namespace globe
