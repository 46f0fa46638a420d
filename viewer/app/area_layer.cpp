// The areas of one view (see area_layer.hpp).
#include "app/area_layer.hpp"

#include <algorithm>
#include <cstdio>

#include "app/bundle_legend.hpp"
#include "app/vector_settle.hpp"
#include "render/color.hpp"
#include "runtime/package_open.hpp"
#include "tileformat/feature_table.hpp"
#include "tileformat/json.hpp"

namespace globe::viewer {

namespace {

// The package's looks (runtime/area_package.hpp) as the fill pass's styles.
std::vector<AreaStyle> area_styles(const AreaPackage& p, double opacity) {
  std::vector<AreaStyle> out;
  for (const AreaLook& l : area_looks(p, opacity)) {
    AreaStyle s;
    s.fill = hex_rgba(l.fill);
    s.fill.a = l.visible ? static_cast<float>(std::clamp(l.opacity, 0.0, 1.0)) : 0.0f;
    s.outline = glm::vec3(hex_rgba(l.outline));
    s.outline_px = l.visible ? static_cast<float>(l.outline_px) : 0.0f;
    out.push_back(s);
  }
  return out;
}

}  // namespace

AreaLayer::AreaLayer(const std::string& path, AreaPackage package, double opacity,
                     uint64_t budget_bytes, int width, int height, CrsCross cross)
    : path_(path),
      features_(open_source(path)),
      cache_(path, std::move(package), budget_bytes),
      renderer_(cache_.arena_words(), width, height, cross),
      width_(width),
      height_(height) {
  styles_ = area_styles(cache_.package(), opacity);
  renderer_.set_styles(styles_);
}

size_t AreaLayer::upload_loaded() {
  const std::vector<uint32_t> loaded = cache_.take_loaded();
  for (uint32_t r : loaded) {
    renderer_.upload(cache_.records()[r]);
    cache_.drop_words(r);
  }
  return loaded.size();
}

double AreaLayer::draw(const LayerPass& pass) {
  const ShadingSettings& sh = pass.shading;
  const bool lens = sh.lens_shows == ShadingSettings::LensShows::kLines;
  renderer_.set_lens_only(float(sh.lens_x), float(sh.lens_y), float(lens ? sh.lens_radius : 0.0));
  const double ms = draw_settled(
      cache_, pass.loading, [&] { return upload_loaded(); },
      [&](VectorFeedback& fb) {
        return renderer_.draw(pass.g, pass.view, pass.world, cache_, ++frame_, fb);
      },
      [&](const VectorFeedback& fb) { tiles_used_ = fb.used.size(); });
  if (cache_.package().meta.choropleth) {
    queue_legend();
    overlay_.draw(renderer_.output_fbo(), width_, height_);
  }
  return ms;
}

void AreaLayer::queue_legend() {
  const tileformat::Choropleth& c = *cache_.package().meta.choropleth;
  std::vector<LegendEntry> rows;
  for (size_t i = c.classes.size(); i-- > 0;)  // highest on top
    rows.push_back({glm::vec4(glm::vec3(styles_[i + 1].fill), 1), 0,
                    short_weight(c.classes[i].min) + " - " + short_weight(c.classes[i].max)});
  if (c.no_data > 0) rows.push_back({glm::vec4(glm::vec3(styles_[0].fill), 1), 0, "no data"});
  queue_legend_box(
      c.field + (c.denominator.empty() ? "" : " / " + c.denominator) + " (" + c.method + ")", rows,
      12, height_, overlay_);
}

std::optional<uint64_t> AreaLayer::feature_at(int x, int y) const {
  const auto [record, polygon] = renderer_.pick(x, y);
  if (record == 0 || polygon == 0 || !cache_.live(record - 1)) return std::nullopt;
  const DecodedAreaTile& t = cache_.records()[record - 1].tile;
  if (polygon - 1 >= t.polygon_feature.size()) return std::nullopt;
  return t.feature_ids.at(t.polygon_feature[polygon - 1]);
}

std::pair<std::string, std::string> AreaLayer::feature_record(uint64_t id) const {
  try {
    if (const auto f = tileformat::FeatureTableReader(package_file(*features_)).get(int64_t(id)))
      return {f->layer, f->properties};
  } catch (const std::exception& e) {
    std::fprintf(stderr, "globe-view: %s: feature %llu: %s\n", path_.c_str(),
                 static_cast<unsigned long long>(id), e.what());
  }
  return {"", "{}"};
}

std::string AreaLayer::pick(int x, int y, bool) {
  const std::optional<uint64_t> id = feature_at(x, y);
  if (!id) return "";
  const auto [layer, properties] = feature_record(*id);
  const std::string text = "area " + std::to_string(*id) + " (" + layer + "): " + properties;
  return text.size() > 200 ? text.substr(0, 197) + "..." : text;
}

std::string AreaLayer::pick_json(int x, int y) {
  const std::optional<uint64_t> id = feature_at(x, y);
  if (!id) return "null";
  const auto [layer, properties] = feature_record(*id);
  return "{\"id\": " + std::to_string(*id) + ", \"layer\": \"" + tileformat::json_escape(layer) +
         "\", \"attributes\": " + (properties.empty() ? "{}" : properties) + "}";
}

std::string AreaLayer::stats_json(double ms) const {
  const ArenaCacheStats s = cache_.stats();
  char text[512];
  std::snprintf(
      text, sizeof text,
      ", \"areas_ms\": %.3f, \"area_tiles_used\": %zu, \"area_tiles_resident\": %zu, "
      "\"area_tiles_empty\": %zu, \"area_bytes\": %llu, \"area_budget_bytes\": %llu, "
      "\"area_tiles_loaded\": %llu, \"area_evictions\": %llu, "
      "\"broken_area_tiles\": %llu",
      ms, tiles_used_, s.resident, s.known_empty, static_cast<unsigned long long>(s.resident_bytes),
      static_cast<unsigned long long>(s.budget_bytes), static_cast<unsigned long long>(s.loaded),
      static_cast<unsigned long long>(s.evictions), static_cast<unsigned long long>(s.broken));
  return text;
}

}  // namespace globe::viewer
