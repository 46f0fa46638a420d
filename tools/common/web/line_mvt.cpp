// Line-cluster tiles as Mapbox Vector Tiles (see line_mvt.hpp).
#include "web/line_mvt.hpp"

#include <cmath>
#include <cstdio>

#include "runtime/errors.hpp"
#include "tileformat/error.hpp"
#include "tileformat/json.hpp"
#include "tileformat/line_tile.hpp"

namespace globe::web {
namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace

// A MapLibre style (version 8) drawing the classes as the viewer does:
// casings under fills, class ids in order (higher on top).

std::string line_style_json(const LinePackage& pkg,
                            const std::map<std::string, std::set<uint32_t>>& classes_in,
                            const std::string& source_url, const StyleGlyphs& glyphs) {
  std::string out = "{\"version\":8,\"name\":\"" + tileformat::json_escape(pkg.meta.common.name) +
                    "\"" + style_glyphs_member(glyphs) +
                    ",\"sources\":{\"lines\":{\"type\":\"vector\",\"url\":\"" +
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
  // The names along the lines, over every line (MapLibre places them on the
  // line's course, upright, where it bends less than 45 degrees).
  if (!glyphs.empty())
    for (const auto& [layer, classes] : classes_in) {
      out += first ? "" : ",";
      first = false;
      out += label_layer_json(layer + ":labels", "lines", layer, glyphs,
                              ",\"symbol-placement\":\"line\",\"text-max-angle\":45,"
                              "\"text-keep-upright\":true");
    }
  return out + "]}";
}

LineMvtEncoder::LineMvtEncoder(LinePackage& package)
    : package_(package),
      labels_(package.file()),
      features_(package.file(), "lines", {"class"}, {}, &labels_) {}

LineMvtEncoder::~LineMvtEncoder() = default;

std::vector<uint8_t> LineMvtEncoder::encode(tileformat::TileId id, std::span<const uint8_t> blob) {
  tileformat::LineTile t;
  try {
    t = tileformat::decode_line_tile(blob);
  } catch (const tileformat::FormatError& e) {
    throw InputError(package_.reader->path() + ": tile " + id.str() + ": " + e.what() +
                     "; check the package with globe-vectorize validate");
  }
  std::vector<MvtLayer> layers;
  std::map<std::string, size_t> layer_of;
  auto layer = [&](const std::string& name, uint32_t cls) -> MvtLayer& {
    auto [at, fresh] = layer_of.try_emplace(name, layers.size());
    if (fresh) layers.emplace_back(name, t.extent);
    classes_in_[name].insert(cls);
    return layers[at->second];
  };
  auto tags_of = [&](uint64_t fid, uint32_t cls) {
    MvtTags tags = features_.get(fid).tags;
    MvtValue c;
    c.text = cls < package_.classes.size() ? package_.classes[cls].name : std::to_string(cls);
    tags.insert(tags.begin(), {"class", c});
    features_.note_fields(features_.get(fid).layer, tags);
    return tags;
  };
  std::vector<MvtPoint> line;
  for (const tileformat::LineRun& r : t.runs) {
    const uint64_t fid = t.feature_ids[r.feature];
    line.clear();
    for (uint32_t v = 0; v < r.vertex_count; ++v)
      line.push_back({t.vertices[r.first_vertex + v].x, t.vertices[r.first_vertex + v].y});
    ++features_count_;
    if (!layer(features_.get(fid).layer, r.class_id)
             .add_line(fid, line, tags_of(fid, r.class_id))) {
      ++zero_length_;
      features_.fields_of(features_.get(fid).layer)["zero_length"] = "Boolean";
    }
  }
  for (const tileformat::LinePoint& p : t.points) {
    const uint64_t fid = t.feature_ids[p.feature];
    layer(features_.get(fid).layer, p.class_id)
        .add_point(fid, {p.at.x, p.at.y}, tags_of(fid, p.class_id));
    ++features_count_;
  }
  return encode_mvt(layers);
}

}  // namespace globe::web
