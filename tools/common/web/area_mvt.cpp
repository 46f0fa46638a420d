// Area tiles as Mapbox Vector Tiles (see area_mvt.hpp).
#include "web/area_mvt.hpp"

#include <cmath>
#include <cstdio>

#include "runtime/errors.hpp"
#include "tileformat/area_tile.hpp"
#include "tileformat/error.hpp"
#include "tileformat/json.hpp"

namespace globe::web {
namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string quoted(const std::string& s) {
  return "\"" + tileformat::json_escape(s) + "\"";
}

// The choropleth's value of a feature from its attributes; NaN if absent.
double choropleth_value(const tileformat::Choropleth& c, const tileformat::JsonValue& props) {
  auto get = [&](const std::string& key) {
    const tileformat::JsonValue* v = props.is_object() ? props.find(key) : nullptr;
    return v && v->is_number() ? v->number() : std::nan("");
  };
  const double v = get(c.field);
  if (c.denominator.empty()) return v;
  const double d = get(c.denominator);
  return d != 0 ? v / d : std::nan("");
}

}  // namespace

std::string area_label_layer(const AreaPackage& package) {
  std::string name = "labels";
  for (const tileformat::LineLayerInfo& l : package.meta.layers)
    if (l.name == name) name = "labels_points";
  return name;
}

AreaMvtEncoder::AreaMvtEncoder(AreaPackage& package)
    : package_(package),
      labels_(package.file()),
      label_layer_(area_label_layer(package)),
      features_(
          package.file(), "areas", {"class", "value"},
          [&package](const tileformat::JsonValue& props, MvtTags& tags) {
            // A choropleth's value, as its classes were made from.
            if (!package.meta.choropleth) return;
            const double v = choropleth_value(*package.meta.choropleth, props);
            if (!std::isfinite(v)) return;
            MvtValue m;
            m.kind = MvtValue::Kind::kDouble;
            m.number = v;
            tags.emplace_back("value", m);
          },
          &labels_) {}

AreaMvtEncoder::~AreaMvtEncoder() = default;

std::vector<uint8_t> AreaMvtEncoder::encode(tileformat::TileId id, std::span<const uint8_t> blob) {
  tileformat::AreaTile t;
  try {
    t = tileformat::decode_area_tile(blob);
  } catch (const tileformat::FormatError& e) {
    throw InputError(package_.reader->path() + ": tile " + id.str() + ": " + e.what() +
                     "; check the package with globe-vectorize validate");
  }
  std::vector<MvtLayer> layers;
  std::map<std::string, size_t> layer_of;
  const std::vector<uint32_t> offsets = t.ring_offsets();
  std::vector<std::vector<MvtPoint>> rings;
  std::set<uint64_t> drawn;  // the features of the tile, for their label points
  for (size_t p = 0; p < t.polygons.size();) {
    // One MVT feature for all polygons of a feature (they are consecutive).
    const uint32_t feature_index = t.polygons[p].feature, cls = t.polygons[p].class_id;
    rings.clear();
    for (; p < t.polygons.size() && t.polygons[p].feature == feature_index; ++p)
      for (uint32_t r = t.polygons[p].first_ring;
           r < t.polygons[p].first_ring + t.polygons[p].ring_count; ++r) {
        rings.emplace_back();
        for (uint32_t v = offsets[r]; v < offsets[r + 1]; ++v)
          rings.back().push_back({t.vertices[v].x, t.vertices[v].y});
      }
    const uint64_t fid = t.feature_ids[feature_index];
    const FeatureTags::Feature& info = features_.get(fid);
    MvtTags tags = info.tags;
    MvtValue c;
    if (package_.meta.choropleth) {
      c.kind = MvtValue::Kind::kInt;
      c.integer = cls;
    } else {
      c.text = cls < package_.classes.size() ? package_.classes[cls].name : std::to_string(cls);
    }
    tags.insert(tags.begin(), {"class", c});
    features_.note_fields(info.layer, tags);
    auto [at, fresh] = layer_of.try_emplace(info.layer, layers.size());
    if (fresh) layers.emplace_back(info.layer, t.extent);
    classes_in_[info.layer].insert(cls);
    layers[at->second].add_polygon(fid, rings, tags);
    drawn.insert(fid);
    ++features_count_;
  }
  // Each label point in the one tile that holds its anchor, if its feature
  // is drawn at this zoom (a polygon below a zoom's grid is not).
  if (!labels_.empty()) {
    MvtLayer points(label_layer_, t.extent);
    for (const MvtLabels::Anchor& a : labels_.anchors_in(id, t.extent)) {
      if (!drawn.count(a.feature)) continue;
      MvtValue name, rank;
      name.text = *labels_.text(a.feature);
      rank.kind = MvtValue::Kind::kInt;
      rank.integer = a.rank;
      const MvtTags tags{{"name", name}, {"rank", rank}};
      features_.note_fields(label_layer_, tags);
      points.add_point(a.feature, a.at, tags);
    }
    if (!points.empty()) layers.push_back(std::move(points));
  }
  return encode_mvt(layers);
}

std::string area_style_json(const AreaPackage& pkg,
                            const std::map<std::string, std::set<uint32_t>>& classes_in,
                            const std::string& source_url, const StyleGlyphs& glyphs) {
  std::string out = "{\"version\":8,\"name\":" + quoted(pkg.meta.common.name) +
                    style_glyphs_member(glyphs) +
                    ",\"sources\":{\"areas\":{\"type\":\"vector\",\"url\":" + quoted(source_url) +
                    "}},\"layers\":[";
  bool first = true;
  auto layer = [&](const std::string& id, const std::string& type, const std::string& source_layer,
                   const std::string& filter, const std::string& paint) {
    out += (first ? "" : ",") + std::string("{\"id\":") + quoted(id) + ",\"type\":\"" + type +
           "\",\"source\":\"areas\",\"source-layer\":" + quoted(source_layer) +
           (filter.empty() ? "" : ",\"filter\":" + filter) + ",\"paint\":{" + paint + "}}";
    first = false;
  };
  const std::vector<AreaLook> looks = area_looks(pkg, kAreaWebFillOpacity);
  for (const auto& [name, classes] : classes_in) {
    if (const auto& c = pkg.meta.choropleth) {
      // step: the first colour below the second class's lower bound, then
      // each class's colour from its lower bound on (classes are [min, max)).
      std::string step = "[\"step\",[\"get\",\"value\"]," + quoted(looks[1].fill);
      for (size_t i = 1; i < c->classes.size(); ++i)
        step += "," + number(c->classes[i].min) + "," + quoted(looks[i + 1].fill);
      step += "]";
      layer(name + "/no-data", "fill", name, "[\"!\",[\"has\",\"value\"]]",
            "\"fill-color\":" + quoted(looks[0].fill) +
                ",\"fill-opacity\":" + number(looks[0].opacity));
      layer(name + "/choropleth", "fill", name, "[\"has\",\"value\"]",
            "\"fill-color\":" + step + ",\"fill-opacity\":" + number(looks[1].opacity));
    } else {
      for (uint32_t k : classes) {
        if (k >= looks.size() || !looks[k].visible) continue;
        layer(name + "/" + pkg.classes[k].name, "fill", name,
              "[\"==\",[\"get\",\"class\"]," + quoted(pkg.classes[k].name) + "]",
              "\"fill-color\":" + quoted(looks[k].fill) +
                  ",\"fill-opacity\":" + number(looks[k].opacity));
      }
    }
  }
  // The outlines over every fill: one per class look (a choropleth's share one).
  for (const auto& [name, classes] : classes_in) {
    if (pkg.meta.choropleth) {
      layer(name + "/outline", "line", name, "",
            "\"line-color\":" + quoted(looks[0].outline) + ",\"line-width\":" +
                number(looks[0].outline_px) + ",\"line-opacity\":" + number(kAreaWebFillOpacity));
      continue;
    }
    for (uint32_t k : classes) {
      if (k >= looks.size() || !looks[k].visible || looks[k].outline_px <= 0) continue;
      layer(name + "/" + pkg.classes[k].name + "/outline", "line", name,
            "[\"==\",[\"get\",\"class\"]," + quoted(pkg.classes[k].name) + "]",
            "\"line-color\":" + quoted(looks[k].outline) + ",\"line-width\":" +
                number(looks[k].outline_px) + ",\"line-opacity\":" + number(kAreaWebFillOpacity));
    }
  }
  // The names over everything, in rank order where they collide; long names
  // wrapped at 8 ems.
  if (!glyphs.empty())
    out += (first ? "" : ",") +
           label_layer_json("labels", "areas", area_label_layer(pkg), glyphs,
                            ",\"symbol-sort-key\":[\"get\",\"rank\"],\"text-max-width\":8");
  return out + "]}";
}

}  // namespace globe::web
