// Package metadata (see metadata.hpp).
#include "tileformat/metadata.hpp"

#include <algorithm>
#include <charconv>
#include <sstream>

#include "tileformat/blob_header.hpp"
#include "tileformat/error.hpp"
#include "tileformat/json.hpp"
#include "tileformat/line_tile.hpp"
#include "tileformat/package.hpp"

namespace tileformat {

std::string build_description(const std::string& what, const std::string& program,
                              const std::vector<InputFile>& inputs) {
  std::string first = inputs.empty() ? std::string() : inputs[0].name;
  if (const auto slash = first.rfind('/'); slash != std::string::npos) first.erase(0, slash + 1);
  return what + " built by " + program + " from " + first +
         (inputs.size() > 1 ? " and " + std::to_string(inputs.size() - 1) + " more" : "");
}

std::string metadata_number(double v, int digits) {
  if (digits == 0) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
  }
  std::ostringstream o;
  o.precision(digits);
  o << v;
  return o.str();
}

namespace {

// ---- writing ----

// "west,south,east,north", each number rounded, then clamped to `lim`, so
// that rounding never takes it past what readers accept.
std::string bounds_text(const Bounds& ll, const Bounds& lim, int digits) {
  auto one = [&](double v, double lo, double hi) {
    const std::string text = metadata_number(v, digits);
    const double back = std::stod(text);
    if (back < lo) return metadata_number(lo, 0);
    if (back > hi) return metadata_number(hi, 0);
    return text;
  };
  return one(ll.min_x, lim.min_x, lim.max_x) + "," + one(ll.min_y, lim.min_y, lim.max_y) + "," +
         one(ll.max_x, lim.min_x, lim.max_x) + "," + one(ll.max_y, lim.min_y, lim.max_y);
}

MetadataMap common_keys(const CommonMetadata& m) {
  MetadataMap meta;
  if (m.has_tiling) m.tiling.to_metadata(meta);
  // The data's bounds computed from the tiling's extent can overshoot it by
  // a rounding error (-180.00000000000003): clamp to the tiling's range.
  const Bounds lim = m.tiling.lonlat_limits();
  const Bounds ll{std::clamp(m.lonlat.min_x, lim.min_x, lim.max_x),
                  std::clamp(m.lonlat.min_y, lim.min_y, lim.max_y),
                  std::clamp(m.lonlat.max_x, lim.min_x, lim.max_x),
                  std::clamp(m.lonlat.max_y, lim.min_y, lim.max_y)};
  meta["name"] = m.name;
  meta["format"] = m.format;
  meta["type"] = m.type;
  meta["version"] = "1";
  meta["description"] = m.description;
  meta["bounds"] = bounds_text(ll, lim, m.bounds_digits);
  meta["center"] = metadata_number((ll.min_x + ll.max_x) / 2) + "," +
                   metadata_number((ll.min_y + ll.max_y) / 2) + "," + std::to_string(m.center_zoom);
  meta["minzoom"] = std::to_string(m.min_zoom);
  meta["maxzoom"] = std::to_string(m.max_zoom);
  meta["globe:format_version"] = std::to_string(kFormatVersion);
  meta["globe:generator"] = m.generator;
  meta["globe:command_line"] = m.command_line;
  std::string inputs = "[";
  for (size_t i = 0; i < m.inputs.size(); ++i)
    inputs += (i ? "," : "") + std::string("{\"name\":\"") + json_escape(m.inputs[i].name) +
              "\",\"bytes\":" + std::to_string(m.inputs[i].bytes) + "}";
  meta["globe:inputs"] = inputs + "]";
  if (!m.left_out.empty()) meta["globe:left_out"] = m.left_out;
  return meta;
}

// ---- reading ----

class Keys {
 public:
  Keys(const MetadataMap& meta, const char* section) : meta_(meta), section_(section) {}

  std::optional<std::string> find(const std::string& key) const {
    auto it = meta_.find(key);
    if (it == meta_.end()) return std::nullopt;
    return it->second;
  }
  std::string text(const std::string& key) const {
    auto v = find(key);
    if (!v) throw FormatError(section_, "metadata key " + key + " is missing");
    return *v;
  }
  double number(const std::string& key) const {
    const std::string v = text(key);
    try {
      return std::stod(v);
    } catch (const std::exception&) {
      throw FormatError(section_, "metadata key " + key + " is not a number");
    }
  }
  int integer(const std::string& key) const { return static_cast<int>(number(key)); }
  JsonValue json(const std::string& key) const {
    try {
      return JsonValue::parse(text(key));
    } catch (const JsonError& e) {
      throw FormatError(section_, "metadata " + key + " is not valid JSON (" + e.what() + ")");
    }
  }
  const char* section() const { return section_; }

 private:
  const MetadataMap& meta_;
  const char* section_;
};

std::optional<Bounds> parse_bounds(const std::string& text) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string item;
  try {
    while (std::getline(ss, item, ','))
      v.push_back(std::stod(item));
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (v.size() != 4) return std::nullopt;
  return Bounds{v[0], v[1], v[2], v[3]};
}

// A JSON member of an array element: what `field` holds, as a string or a
// non-negative integer; throws FormatError.
const JsonValue& member(const JsonValue& o, const char* field, const std::string& key,
                        const char* section) {
  const JsonValue* v = o.is_object() ? o.find(field) : nullptr;
  if (!v) throw FormatError(section, "metadata " + key + ": an entry lacks \"" + field + "\"");
  return *v;
}

template <typename T, typename Fn>
std::vector<T> read_array(const Keys& keys, const std::string& key, Fn one) {
  std::vector<T> out;
  const JsonValue doc = keys.json(key);
  try {
    for (const JsonValue& e : doc.array())
      out.push_back(one(e));
  } catch (const JsonError& e) {
    throw FormatError(keys.section(), "metadata " + key + ": " + e.what());
  }
  return out;
}

// globe:layers of line and area packages (§7.4): the source layers and
// their feature counts, as JSON.
std::string layers_json(const std::vector<LineLayerInfo>& layers) {
  std::string out = "[";
  for (size_t i = 0; i < layers.size(); ++i)
    out += (i ? "," : "") + std::string("{\"name\":\"") + json_escape(layers[i].name) +
           "\",\"source\":\"" + json_escape(layers[i].source) +
           "\",\"features\":" + std::to_string(layers[i].features) + "}";
  return out + "]";
}

std::vector<LineLayerInfo> read_layers(const Keys& k, const char* section) {
  return read_array<LineLayerInfo>(k, "globe:layers", [&](const JsonValue& e) {
    return LineLayerInfo{
        member(e, "name", "globe:layers", section).string(),
        member(e, "source", "globe:layers", section).string(),
        static_cast<uint64_t>(member(e, "features", "globe:layers", section).number())};
  });
}

void read_common(const Keys& k, const MetadataMap& meta, CommonMetadata& m) {
  m.format = k.text("format");
  m.name = k.find("name").value_or("");
  m.type = k.find("type").value_or("");
  m.description = k.find("description").value_or("");
  m.has_tiling = k.find("globe:scheme").has_value();
  m.tiling = m.has_tiling ? Tiling::from_metadata(meta) : Tiling::webmercator();
  m.min_zoom = k.integer("minzoom");
  m.max_zoom = k.integer("maxzoom");
  const auto bounds = k.find("bounds");
  const auto parsed = bounds ? parse_bounds(*bounds) : std::nullopt;
  m.has_bounds = parsed.has_value();
  m.lonlat = parsed.value_or(m.tiling.lonlat_limits());
  if (auto center = k.find("center")) {
    const auto comma = center->rfind(',');
    try {
      if (comma != std::string::npos) m.center_zoom = std::stoi(center->substr(comma + 1));
    } catch (const std::exception&) {
    }
  }
  m.generator = k.find("globe:generator").value_or("");
  m.command_line = k.find("globe:command_line").value_or("");
  m.left_out = k.find("globe:left_out").value_or("");
  if (k.find("globe:inputs"))
    m.inputs = read_array<InputFile>(k, "globe:inputs", [&](const JsonValue& e) {
      return InputFile{
          member(e, "name", "globe:inputs", k.section()).string(),
          static_cast<uint64_t>(member(e, "bytes", "globe:inputs", k.section()).number())};
    });
}

}  // namespace

MetadataMap to_metadata(const TerrainMetadata& m) {
  MetadataMap meta = common_keys(m.common);
  meta["globe:resampling"] = m.resampling;
  meta["globe:block_size"] = std::to_string(m.block_size);
  meta["globe:kpatch_lattice"] = std::to_string(m.lattice);
  meta["globe:height_step"] = metadata_number(m.height_step);
  meta["globe:fill_height"] = metadata_number(m.fill_height);
  return meta;
}

MetadataMap to_metadata(const ImageMetadata& m) {
  MetadataMap meta = common_keys(m.common);
  meta["globe:resampling"] = m.resampling;
  meta["globe:tile_size"] = std::to_string(m.tile_size);
  meta["globe:colour_bands"] = std::to_string(m.colour_bands);
  if (m.quality) meta["globe:quality"] = std::to_string(*m.quality);
  if (m.png_level) meta["globe:png_level"] = std::to_string(*m.png_level);
  if (m.scale)
    meta["globe:scale"] = metadata_number(m.scale->first) + "," + metadata_number(m.scale->second);
  return meta;
}

MetadataMap to_metadata(const LineMetadata& m) {
  MetadataMap meta = common_keys(m.common);
  meta["globe:extent"] = std::to_string(m.extent);
  meta["globe:cluster_grid"] = std::to_string(m.cluster_grid);
  meta["globe:simplify_px"] = metadata_number(m.simplify_px);
  meta["globe:tile_px"] = metadata_number(m.tile_px);
  meta["globe:features"] = std::to_string(m.features);
  meta["globe:classes"] = m.classes_json;
  meta["globe:layers"] = layers_json(m.layers);
  if (!m.bundle_json.empty()) meta["globe:bundle"] = m.bundle_json;
  return meta;
}

CommonMetadata read_common_metadata(const MetadataMap& meta) {
  CommonMetadata m;
  read_common(Keys(meta, "3.2"), meta, m);
  return m;
}

MetadataMap to_metadata(const AnalysisMetadata& m) {
  MetadataMap meta = common_keys(m.common);
  meta["globe:block_size"] = std::to_string(m.block_size);
  std::string names;
  for (AnalysisLayer l : m.layers)
    names += (names.empty() ? "" : ",") + std::string(analysis_layer_info(l).name);
  meta["globe:analysis_layers"] = names;
  meta["globe:terrain"] = m.terrain;
  meta["globe:height_step"] = metadata_number(m.height_step);
  if (m.skyview_directions > 0) {
    meta["globe:skyview_directions"] = std::to_string(m.skyview_directions);
    meta["globe:skyview_radius_m"] = metadata_number(m.skyview_radius_m);
    std::string by_zoom;
    for (const auto& [z, r] : m.skyview_radius_by_zoom)
      by_zoom += (by_zoom.empty() ? "" : ",") + std::to_string(z) + ":" + metadata_number(r);
    if (!by_zoom.empty()) meta["globe:skyview_radius_by_zoom"] = by_zoom;
  }
  if (!m.flow_method.empty()) meta["globe:flow_method"] = m.flow_method;
  return meta;
}

AnalysisMetadata read_analysis_metadata(const MetadataMap& meta) {
  const Keys k(meta, "9");
  AnalysisMetadata m;
  read_common(Keys(meta, "3.2"), meta, m.common);
  if (!m.common.has_tiling) Tiling::from_metadata(meta);  // names the missing key
  m.block_size = k.integer("globe:block_size");
  const std::string names = k.find("globe:analysis_layers").value_or("");
  size_t start = 0;
  while (start <= names.size()) {
    const size_t comma = std::min(names.find(',', start), names.size());
    const std::string name = names.substr(start, comma - start);
    const auto layer = analysis_layer_by_name(name);
    if (!layer) throw FormatError("9", "globe:analysis_layers: unknown layer '" + name + "'");
    m.layers.push_back(*layer);
    start = comma + 1;
  }
  m.terrain = k.find("globe:terrain").value_or("");
  m.height_step = k.find("globe:height_step") ? k.number("globe:height_step") : 0.0;
  if (k.find("globe:skyview_directions")) {
    m.skyview_directions = k.integer("globe:skyview_directions");
    m.skyview_radius_m = k.number("globe:skyview_radius_m");
    const std::string by_zoom = k.find("globe:skyview_radius_by_zoom").value_or("");
    // Items as in globe:analysis_layers: a trailing comma is an empty item.
    for (size_t at = 0; !by_zoom.empty() && at <= by_zoom.size();) {
      const size_t comma = std::min(by_zoom.find(',', at), by_zoom.size());
      const std::string item = by_zoom.substr(at, comma - at);
      const size_t colon = std::min(item.find(':'), item.size());
      int z = -1;
      double r = -1;
      const char* b = item.data();
      const auto zr = std::from_chars(b, b + colon, z);
      const auto rr = std::from_chars(b + std::min(colon + 1, item.size()), b + item.size(), r);
      if (zr.ec != std::errc() || zr.ptr != b + colon || rr.ec != std::errc() ||
          rr.ptr != b + item.size() || z < 0 || z > 40 || !(r >= 0))
        throw FormatError("9", "globe:skyview_radius_by_zoom: '" + item + "' is not ZOOM:METRES");
      m.skyview_radius_by_zoom.emplace_back(z, r);
      at = comma + 1;
    }
  }
  m.flow_method = k.find("globe:flow_method").value_or("");
  return m;
}

TerrainMetadata read_terrain_metadata(const MetadataMap& meta) {
  const Keys k(meta, "3.2");
  TerrainMetadata m;
  read_common(k, meta, m.common);
  if (!m.common.has_tiling) Tiling::from_metadata(meta);  // names the missing key
  m.resampling = k.find("globe:resampling").value_or("");
  m.block_size = k.integer("globe:block_size");
  m.lattice = k.integer("globe:kpatch_lattice");
  m.height_step = k.number("globe:height_step");
  m.fill_height = k.find("globe:fill_height") ? k.number("globe:fill_height") : 0.0;
  return m;
}

ImageMetadata read_image_metadata(const MetadataMap& meta) {
  const Keys k(meta, "8");
  ImageMetadata m;
  read_common(Keys(meta, "3.2"), meta, m.common);
  const auto format = parse_image_format(m.common.format);
  if (!format) throw FormatError("8", "format '" + m.common.format + "' is not png, jpg or webp");
  m.format = *format;
  m.resampling = k.find("globe:resampling").value_or("");
  if (!m.common.has_tiling) {  // another tool's MBTiles: the tiles say
    m.tile_size = 0;
    m.colour_bands = 0;
    return m;
  }
  m.tile_size = k.integer("globe:tile_size");
  m.colour_bands = k.integer("globe:colour_bands");
  if ((m.tile_size != 256 && m.tile_size != 512) || (m.colour_bands != 1 && m.colour_bands != 3))
    throw FormatError("8", "globe:tile_size must be 256 or 512 and globe:colour_bands 1 or 3");
  if (k.find("globe:quality")) m.quality = k.integer("globe:quality");
  if (k.find("globe:png_level")) m.png_level = k.integer("globe:png_level");
  if (auto scale = k.find("globe:scale")) {
    const auto comma = scale->find(',');
    try {
      m.scale =
          std::make_pair(std::stod(scale->substr(0, comma)), std::stod(scale->substr(comma + 1)));
    } catch (const std::exception&) {
      throw FormatError("8", "metadata globe:scale is not 'min,max'");
    }
  }
  return m;
}

LineMetadata read_line_metadata(const MetadataMap& meta) {
  const Keys k(meta, "3.2");
  LineMetadata m;
  read_common(k, meta, m.common);
  if (!m.common.has_tiling) Tiling::from_metadata(meta);  // names the missing key
  m.extent = k.integer("globe:extent");
  m.cluster_grid = k.integer("globe:cluster_grid");
  m.simplify_px = k.find("globe:simplify_px") ? k.number("globe:simplify_px") : 0.0;
  m.tile_px = k.find("globe:tile_px") ? k.number("globe:tile_px") : 0.0;
  m.features = k.find("globe:features") ? static_cast<uint64_t>(k.number("globe:features")) : 0;
  const Keys k74(meta, "7.4");
  m.classes_json = k74.text("globe:classes");
  if (k.find("globe:layers")) m.layers = read_layers(k74, "7.4");
  if (k.find("globe:bundle")) m.bundle_json = Keys(meta, "7.5").text("globe:bundle");
  return m;
}

MetadataMap to_metadata(const PointMetadata& m) {
  MetadataMap meta = common_keys(m.common);
  meta["globe:extent"] = std::to_string(m.extent);
  meta["globe:cluster_grid"] = std::to_string(m.cluster_grid);
  meta["globe:tile_px"] = metadata_number(m.tile_px);
  meta["globe:chart_max_px"] = metadata_number(m.chart_max_px);
  std::string fields = "[";
  for (size_t i = 0; i < m.fields.size(); ++i)
    fields += (i ? ",\"" : "\"") + json_escape(m.fields[i]) + "\"";
  meta["globe:fields"] = fields + "]";
  meta["globe:aggregate"] = m.aggregate == PointAggregate::kSum ? "sum" : "mean";
  meta["globe:merge_px"] = metadata_number(m.merge_px);
  meta["globe:signed"] = m.signed_values ? "1" : "0";
  meta["globe:label_field"] = m.label_field;
  meta["globe:features"] = std::to_string(m.features);
  std::string zooms = "[";
  for (size_t i = 0; i < m.zooms.size(); ++i) {
    const PointZoomStats& z = m.zooms[i];
    zooms += (i ? "," : "") + std::string("{\"zoom\":") + std::to_string(z.zoom) +
             ",\"places\":" + std::to_string(z.places) +
             ",\"max_total\":" + metadata_number(z.max_total, 0) +
             ",\"max_value\":" + metadata_number(z.max_value, 0) + "}";
  }
  meta["globe:zoom_stats"] = zooms + "]";
  return meta;
}

PointMetadata read_point_metadata(const MetadataMap& meta) {
  const Keys k(meta, "11.4");
  PointMetadata m;
  read_common(k, meta, m.common);
  if (!m.common.has_tiling) Tiling::from_metadata(meta);  // names the missing key
  m.extent = k.integer("globe:extent");
  m.cluster_grid = k.integer("globe:cluster_grid");
  m.tile_px = k.number("globe:tile_px");
  m.chart_max_px = k.number("globe:chart_max_px");
  m.fields =
      read_array<std::string>(k, "globe:fields", [](const JsonValue& e) { return e.string(); });
  if (m.fields.empty()) throw FormatError("11.4", "metadata globe:fields lists no field");
  const std::string aggregate = k.text("globe:aggregate");
  if (aggregate != "sum" && aggregate != "mean")
    throw FormatError("11.4", "metadata globe:aggregate is '" + aggregate + "', not sum or mean");
  m.aggregate = aggregate == "sum" ? PointAggregate::kSum : PointAggregate::kMean;
  m.merge_px = k.number("globe:merge_px");
  m.signed_values = k.text("globe:signed") == "1";
  m.label_field = k.find("globe:label_field").value_or("");
  m.features = static_cast<uint64_t>(k.number("globe:features"));
  m.zooms = read_array<PointZoomStats>(k, "globe:zoom_stats", [&](const JsonValue& e) {
    return PointZoomStats{
        static_cast<int>(member(e, "zoom", "globe:zoom_stats", "11.4").number()),
        static_cast<uint64_t>(member(e, "places", "globe:zoom_stats", "11.4").number()),
        member(e, "max_total", "globe:zoom_stats", "11.4").number(),
        member(e, "max_value", "globe:zoom_stats", "11.4").number()};
  });
  for (const PointZoomStats& z : m.zooms)
    if (z.zoom < m.common.min_zoom || z.zoom > m.common.max_zoom)
      throw FormatError("11.4", "metadata globe:zoom_stats names zoom " + std::to_string(z.zoom) +
                                    " outside minzoom..maxzoom");
  return m;
}

MetadataMap to_metadata(const AreaMetadata& m) {
  MetadataMap meta = common_keys(m.common);
  meta["globe:extent"] = std::to_string(m.extent);
  meta["globe:buffer"] = std::to_string(m.buffer);
  meta["globe:simplify_px"] = metadata_number(m.simplify_px);
  meta["globe:tile_px"] = metadata_number(m.tile_px);
  meta["globe:features"] = std::to_string(m.features);
  meta["globe:classes"] = m.classes_json;
  meta["globe:layers"] = layers_json(m.layers);
  meta["globe:repaired"] = std::to_string(m.repaired);
  if (const auto& c = m.choropleth) {
    std::string j = "{\"field\":\"" + json_escape(c->field) + "\",\"denominator\":\"" +
                    json_escape(c->denominator) + "\",\"method\":\"" + json_escape(c->method) +
                    "\",\"ramp\":\"" + json_escape(c->ramp) + "\",\"classes\":[";
    for (size_t i = 0; i < c->classes.size(); ++i)
      j += (i ? "," : "") + std::string("{\"min\":") + metadata_number(c->classes[i].min) +
           ",\"max\":" + metadata_number(c->classes[i].max) + ",\"color\":\"" +
           json_escape(c->classes[i].color) + "\"}";
    j += "],\"no_data\":{\"color\":\"" + json_escape(c->no_data_color) +
         "\",\"features\":" + std::to_string(c->no_data) + "}}";
    meta["globe:choropleth"] = j;
  }
  return meta;
}

AreaMetadata read_area_metadata(const MetadataMap& meta) {
  const Keys k(meta, "12.3");
  AreaMetadata m;
  read_common(k, meta, m.common);
  if (!m.common.has_tiling) Tiling::from_metadata(meta);  // names the missing key
  m.extent = k.integer("globe:extent");
  m.buffer = k.integer("globe:buffer");
  m.simplify_px = k.number("globe:simplify_px");
  m.tile_px = k.number("globe:tile_px");
  m.features = static_cast<uint64_t>(k.number("globe:features"));
  m.classes_json = k.text("globe:classes");
  m.layers = read_layers(k, "12.3");
  m.repaired = static_cast<uint64_t>(k.number("globe:repaired"));
  if (k.find("globe:choropleth")) {
    const JsonValue doc = k.json("globe:choropleth");
    try {
      Choropleth c;
      auto text = [&](const JsonValue& o, const char* f) {
        return member(o, f, "globe:choropleth", "12.3").string();
      };
      c.field = text(doc, "field");
      c.denominator = text(doc, "denominator");
      c.method = text(doc, "method");
      c.ramp = text(doc, "ramp");
      for (const JsonValue& e : member(doc, "classes", "globe:choropleth", "12.3").array())
        c.classes.push_back({member(e, "min", "globe:choropleth", "12.3").number(),
                             member(e, "max", "globe:choropleth", "12.3").number(),
                             text(e, "color")});
      const JsonValue& nd = member(doc, "no_data", "globe:choropleth", "12.3");
      c.no_data_color = text(nd, "color");
      c.no_data =
          static_cast<uint64_t>(member(nd, "features", "globe:choropleth", "12.3").number());
      if (c.classes.empty()) throw FormatError("12.3", "metadata globe:choropleth has no class");
      m.choropleth = std::move(c);
    } catch (const JsonError& e) {
      throw FormatError("12.3", std::string("metadata globe:choropleth: ") + e.what());
    }
  }
  return m;
}

}  // namespace tileformat
