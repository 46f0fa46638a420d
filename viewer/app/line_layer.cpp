// The lines of one view (see line_layer.hpp).
#include "app/line_layer.hpp"
#include "runtime/package_open.hpp"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "app/color_relief_file.hpp"
#include "app/vector_settle.hpp"
#include "render/color_ramp.hpp"
#include "runtime/errors.hpp"
#include "tileformat/feature_table.hpp"
#include "tileformat/json.hpp"

namespace globe::viewer {

namespace {

// The class picked features are drawn in: over every other (wider, and the
// highest class id wins ties), in a colour no default style uses.
NamedLineStyle highlight_style(const std::vector<NamedLineStyle>& classes) {
  double widest = 2;
  for (const NamedLineStyle& c : classes)
    if (c.style.visible && !c.style.width_in_m) widest = std::max(widest, c.style.width);
  LineStyle s;
  s.color = "#00e5ff";
  s.width = widest + 2;
  s.casing_color = "#08306b";
  s.casing_width = 1;
  return {"highlight", s};
}

std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// A member of a feature's properties as text ("" when absent).
std::string property(const tileformat::JsonValue& props, const char* key) {
  const tileformat::JsonValue* v = props.find(key);
  if (!v) return "";
  return v->is_number() ? number_text(v->number()) : v->is_string() ? v->string() : "";
}

// Per class, the ramp of a class coloured by the ground under it: its
// colour file (UsageError naming it when unreadable) or the built-in one.
std::vector<LineRamp> line_ramps(const std::vector<NamedLineStyle>& classes,
                                 std::pair<double, double> heights) {
  std::vector<LineRamp> out(classes.size());
  for (size_t k = 0; k < classes.size(); ++k) {
    const LineStyle& s = classes[k].style;
    if (s.color_by.empty()) continue;
    const bool slope = s.color_by == "slope";
    ColorRamp ramp;
    if (!s.ramp.empty()) {
      ramp = read_color_relief_file(s.ramp).ramp;
    } else if (slope) {  // as --shading slope: cream to red over 0..45 degrees
      ramp = {"slope (built-in)",
              {{0, false, {255, 255, 217, 255}}, {45, false, {191, 26, 13, 255}}}};
    } else {
      ramp = builtin_ramp("hypsometric", heights.first, heights.second);
    }
    const RampTable t =
        slope ? tabulate(ramp, 0, 90) : tabulate(ramp, heights.first, heights.second);
    LineRamp& r = out[k];
    r.by = slope ? 1 : 2;
    r.lo = static_cast<float>(t.lo), r.hi = static_cast<float>(t.hi);
    r.rgba.resize(LineRamp::kEntries * 4);
    for (int i = 0; i < LineRamp::kEntries; ++i) {
      const int src = i * (RampTable::kEntries - 1) / (LineRamp::kEntries - 1);
      std::copy_n(t.rgba.begin() + src * 4, 4, r.rgba.begin() + i * 4);
    }
  }
  return out;
}

}  // namespace

LineLayer::LineLayer(const std::string& path, LinePackage package,
                     std::optional<std::string> style_path, LineMode mode, uint64_t budget_bytes,
                     int width, int height, CrsCross cross)
    : path_(path),
      style_path_(std::move(style_path)),
      package_styles_(package.classes),
      bundled_(!package.meta.bundle_json.empty()),
      features_(open_source(path)),
      mode_(mode),
      cache_(path, std::move(package), budget_bytes),
      renderer_(cache_.arena_words(), width, height, cross),
      cross_(cross),
      width_(width),
      height_(height),
      legend_(bundle_legend_rows(cache_.package().meta.bundle_json)) {
  styles_ = read_styles();
  renderer_.set_styles(styles_, line_ramps(styles_, heights_));
  if (style_path_) {
    std::error_code ec;
    style_time_ = std::filesystem::last_write_time(*style_path_, ec);
  }
}

std::vector<NamedLineStyle> LineLayer::read_styles() const {
  std::vector<NamedLineStyle> styles = package_styles_;
  if (!style_path_) {
    styles.push_back(highlight_style(styles));
    return styles;
  }
  std::ifstream in(*style_path_);
  if (!in) throw InputError(*style_path_ + ": cannot read the style file");
  std::stringstream text;
  text << in.rdbuf();
  apply_style_json(text.str(), *style_path_, styles);
  styles.push_back(highlight_style(styles));
  return styles;
}

bool LineLayer::reload_style(bool always) {
  if (!style_path_) return false;
  std::error_code ec;
  const auto t = std::filesystem::last_write_time(*style_path_, ec);
  if (!always && (ec || t == style_time_)) return false;
  style_time_ = t;
  try {
    std::vector<NamedLineStyle> styles = read_styles();
    renderer_.set_styles(styles, line_ramps(styles, heights_));
    styles_ = std::move(styles);
    std::fprintf(stderr, "globe-view: styles reloaded from %s\n", style_path_->c_str());
    return true;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "globe-view: %s; keeping the previous styles\n", e.what());
    return false;
  }
}

size_t LineLayer::upload_loaded() {
  const std::vector<uint32_t> loaded = cache_.take_loaded();
  for (uint32_t r : loaded) {
    renderer_.upload(r, cache_.records()[r]);
    if (!heat_) cache_.drop_words(r);  // a heatmap samples the segments on the CPU
  }
  return loaded.size();
}

void LineLayer::set_height_range(double lo, double hi) {
  if (!(hi > lo) || std::pair(lo, hi) == heights_) return;
  heights_ = {lo, hi};
  for (const NamedLineStyle& c : styles_)
    if (c.style.color_by == "height") {
      renderer_.set_styles(styles_, line_ramps(styles_, heights_));
      return;
    }
}

void LineLayer::set_mode(LineMode m) {
  if (m != LineMode::kDeferred && cross_ != CrsCross::kSame) {
    std::fprintf(stderr,
                 "globe-view: %s is tiled unlike the terrain; its lines draw per pixel only "
                 "(geometry and lifted lines need the terrain's tiling)\n",
                 path_.c_str());
    return;
  }
  mode_ = m;
}

double LineLayer::draw(const LayerPass& pass) {
  const GBuffer& g = pass.g;
  const View& view = pass.view;
  const WorldFrame& world = pass.world;
  const double exaggeration = pass.shading.exaggeration;
  const TerrainHeights& terrain = pass.heights;
  const ShadingSettings& sh = pass.shading;
  const bool lens = sh.lens_shows == ShadingSettings::LensShows::kLines;
  renderer_.set_lens_only(float(sh.lens_x), float(sh.lens_y), float(lens ? sh.lens_radius : 0.0));
  set_height_range(pass.height_lo, pass.height_hi);
  const double ms = draw_settled(
      cache_, pass.loading, [&] { return upload_loaded(); },
      [&](VectorFeedback& fb) {
        return renderer_.draw(g, view, world, exaggeration, cache_, terrain, mode_, ++frame_, fb);
      },
      [&](const VectorFeedback& fb) {
        tiles_used_ = fb.used.size();
        used_ = fb.used;
      });
  if (heat_) return draw_heatmap(g, view, world, exaggeration, terrain, pass.below_fbo);
  if (!legend_.empty()) {
    queue_bundle_legend(legend_, styles_, height_, overlay_);
    overlay_.draw(renderer_.output_fbo(), width_, height_);
  }
  return ms;
}

void LineLayer::enable_heatmap(const HeatRadius& radius, const HeatmapStyle& style,
                               const WorldFrame& world) {
  heat_ = std::make_unique<ChartRenderer>(width_, height_);
  heat_tiling_ = std::make_unique<LayerTiling>(cache_.package().tiling, cross_, world);
  heat_radius_ = radius;
  heat_style_ = style;
}

double LineLayer::draw_heatmap(const GBuffer& g, const View& view, const WorldFrame& world,
                               double exaggeration, const TerrainHeights& terrain,
                               GLuint under_fbo) {
  if (!terrain.frame) throw std::logic_error("a line heatmap without the terrain's frame");
  // Weights per class: a bundle weight class's middle, else 1.
  std::vector<double> weight(styles_.size(), 1.0);
  for (const LegendRow& row : legend_)
    for (size_t c = 0; c < styles_.size(); ++c)
      if (styles_[c].name == row.class_name) weight[c] = 0.5 * (row.min + row.max);
  // The tiles the frame read, the coarsest where zooms overlap (each
  // stretch of line counts once).
  std::set<tileformat::TileId> ids;
  for (uint32_t r : used_)
    ids.insert(cache_.records()[r].id);
  auto covered = [&](tileformat::TileId id) {
    while (id.z > 0) {
      id = {id.z - 1, id.x / 2, id.y / 2};
      if (ids.count(id)) return true;
    }
    return false;
  };
  const HeatFrame frame(view, world);
  heat_ground_per_m_ = frame.ground_per_m();
  std::vector<ChartInstance> samples;
  for (uint32_t r : used_) {
    const LineRecord& rec = cache_.records()[r];
    if (rec.empty || rec.tile.words.empty() || covered(rec.id)) continue;
    const uint32_t base = rec.tile.grid * rec.tile.grid + 1 + rec.tile.cell_entries;
    const double extent = rec.tile.extent;
    for (uint32_t s = 0; s < rec.tile.segments; ++s) {
      const uint32_t* w = &rec.tile.words[base + size_t(s) * kLineWordsPerSegment];
      const uint32_t cls = w[4];
      if (cls >= styles_.size() || !styles_[cls].style.visible) continue;
      auto at = [&](uint32_t k) {
        return heat_tiling_->tile_to_key(rec.id, std::bit_cast<float>(w[k]) / extent,
                                         std::bit_cast<float>(w[k + 1]) / extent);
      };
      const glm::dvec2 a = at(0), b = at(2);
      const double length = glm::length(world.key_to_world(b.x, b.y, 0, view.origin) -
                                        world.key_to_world(a.x, a.y, 0, view.origin)) /
                            frame.ground_per_m();
      // Samples at most a third of the kernel's radius apart, each standing
      // for its stretch of line.
      const double step = frame.radius_m(0.5 * (a + b), heat_radius_) / 3;
      const int n = std::max(1, static_cast<int>(std::ceil(length / std::max(step, 1e-9))));
      for (int i = 0; i < n; ++i)
        samples.push_back(
            frame.instance(a + (b - a) * ((i + 0.5) / n), weight[cls] * length / n, heat_radius_));
    }
  }
  heat_->set_instances(samples);
  HeatmapStyle hs = heat_style_;
  hs.margin_world = static_cast<float>(terrain.relief_world);
  return heat_->draw_heatmap(under_fbo, g, view, world, *terrain.frame, terrain, hs, exaggeration);
}

std::optional<uint64_t> LineLayer::feature_at(int x, int y) {
  const auto [record, segment] = renderer_.pick(x, y);
  if (record == 0 || segment == 0 || !cache_.live(record - 1)) return std::nullopt;
  const tileformat::TileId id = cache_.records()[record - 1].id;
  try {
    const auto blob = features_->tile(id);
    if (!blob) return std::nullopt;
    return segment_feature(tileformat::decode_line_tile(*blob), segment - 1);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "globe-view: %s: line tile %s: %s; nothing picked\n", path_.c_str(),
                 id.str().c_str(), e.what());
    return std::nullopt;
  }
}

const LineLayer::BundleIndex& LineLayer::bundle_index() {
  if (bundles_) return *bundles_;
  bundles_ = std::make_unique<BundleIndex>();
  if (!features_->package()) return *bundles_;  // a remote source: no features table
  tileformat::FeatureTableReader table(*features_->package());
  table.for_each([&](int64_t id, const tileformat::FeatureRecord& f) {
    if (f.layer != "connections") return;
    const tileformat::JsonValue props = tileformat::JsonValue::parse(f.properties);
    const tileformat::JsonValue* bundles = props.find("bundles");
    if (!bundles || !bundles->is_array()) return;  // unrouted
    std::vector<uint64_t>& path = bundles_->bundles_of[uint64_t(id)];
    for (const tileformat::JsonValue& b : bundles->array()) {
      path.push_back(uint64_t(b.number()));
      bundles_->connections_of[path.back()].push_back(uint64_t(id));
    }
  });
  return *bundles_;
}

std::string LineLayer::describe(uint64_t feature, std::vector<uint64_t>& lit) {
  std::string text = "feature " + std::to_string(feature);
  try {
    const std::optional<tileformat::FeatureRecord> f =
        tileformat::FeatureTableReader(package_file(*features_)).get(int64_t(feature));
    if (!f) return text;
    const tileformat::JsonValue props = tileformat::JsonValue::parse(f->properties);
    if (bundled_ && f->layer == "bundles") {
      const BundleIndex& index = bundle_index();
      if (auto it = index.connections_of.find(feature); it != index.connections_of.end())
        for (uint64_t c : it->second) {
          const std::vector<uint64_t>& path = index.bundles_of.at(c);
          lit.insert(lit.end(), path.begin(), path.end());
        }
      return "bundle " + std::to_string(feature) + ": weight " + property(props, "weight") + ", " +
             property(props, "count") + " connections";
    }
    if (bundled_ && f->layer == "unrouted")
      return "unrouted " + property(props, "origin") + " - " + property(props, "destination") +
             ": weight " + property(props, "weight") + " (" + property(props, "reason") + ")";
    text += " (" + f->layer + "): " + f->properties;
    return text.size() > 200 ? text.substr(0, 197) + "..." : text;
  } catch (const std::exception& e) {
    // A package without a features table, or a row that is not JSON: the id
    // is all there is to say.
    std::fprintf(stderr, "globe-view: %s: feature %llu: %s\n", path_.c_str(),
                 static_cast<unsigned long long>(feature), e.what());
    return text;
  }
}

std::string LineLayer::pick_json(int x, int y) {
  if (heat_) return "null";
  const std::optional<uint64_t> feature = feature_at(x, y);
  if (!feature) return "null";
  std::string layer, attributes = "{}";
  try {
    if (const auto f =
            tileformat::FeatureTableReader(package_file(*features_)).get(int64_t(*feature))) {
      layer = f->layer;
      if (!f->properties.empty()) attributes = f->properties;
    }
  } catch (const std::exception&) {
    // a package without a features table: the id is all there is
  }
  return "{\"id\": " + std::to_string(*feature) + ", \"layer\": \"" +
         tileformat::json_escape(layer) + "\", \"attributes\": " + attributes + "}";
}

std::string LineLayer::pick(int x, int y, bool highlight) {
  if (heat_) {  // the density there: weight x km of line per km^2
    char buf[80];
    std::snprintf(buf, sizeof buf, "heatmap: %.6g per km2 (weight x km of line)",
                  heat_->density_at(x, y) * heat_ground_per_m_ * heat_ground_per_m_ * 1e3);
    return buf;
  }
  std::vector<uint64_t> lit;
  std::string text;
  if (const std::optional<uint64_t> feature = feature_at(x, y)) {
    lit = {*feature};
    text = describe(*feature, lit);
  }
  if (!highlight) return text;
  std::sort(lit.begin(), lit.end());
  lit.erase(std::unique(lit.begin(), lit.end()), lit.end());
  if (lit != highlighted_) {
    highlighted_ = lit;
    cache_.set_highlight({lit, static_cast<uint32_t>(package_styles_.size())});
  }
  return text;
}

}  // namespace globe::viewer

namespace globe::viewer {

std::string LineLayer::stats_json(double ms) const {
  const LineLayerStats ls = stats();
  char text[768];
  std::snprintf(
      text, sizeof text,
      ", \"lines\": \"%s\", \"lines_ms\": %.3f, \"line_tiles_used\": %zu, "
      "\"line_tiles_resident\": %zu, \"line_tiles_empty\": %zu, \"line_bytes\": %llu, "
      "\"line_budget_bytes\": %llu, \"line_tiles_loaded\": %llu, \"line_evictions\": %llu, "
      "\"broken_line_tiles\": %llu, \"line_bytes_read\": %llu",
      mode_ == LineMode::kDeferred   ? "deferred"
      : mode_ == LineMode::kGeometry ? "geometry"
                                     : "lifted",
      ms, ls.tiles_used, ls.cache.resident, ls.cache.known_empty,
      static_cast<unsigned long long>(ls.cache.resident_bytes),
      static_cast<unsigned long long>(ls.cache.budget_bytes),
      static_cast<unsigned long long>(ls.cache.loaded),
      static_cast<unsigned long long>(ls.cache.evictions),
      static_cast<unsigned long long>(ls.cache.broken),
      static_cast<unsigned long long>(ls.cache.bytes_read));
  return text;
}

}  // namespace globe::viewer
