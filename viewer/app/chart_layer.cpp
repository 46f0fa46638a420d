// Charts of a view (see chart_layer.hpp).
#include "app/chart_layer.hpp"
#include "runtime/package_open.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <unordered_map>

#include <glm/glm.hpp>

#include "app/heat_samples.hpp"
#include "render/color.hpp"
#include "render/point_tile_selection.hpp"
#include "runtime/errors.hpp"
#include "tileformat/feature_table.hpp"
#include "tileformat/json.hpp"

namespace globe::viewer {

using tileformat::TileId;

namespace {

constexpr double kTilePx = 256;

const char* kind_name(ChartKind k) {
  switch (k) {
    case ChartKind::kPie:
      return "pie";
    case ChartKind::kBar:
      return "bar";
    case ChartKind::kStacked:
      return "stacked";
    case ChartKind::kColumn:
      return "column";
  }
  return "?";
}

bool needs_shares(ChartKind k) {
  return k == ChartKind::kPie || k == ChartKind::kStacked;
}

std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace

ChartLayer::ChartLayer(PointPackage package, const ChartSettings& settings, uint64_t budget_bytes,
                       int width, int height, CrsCross cross, const WorldFrame& world)
    : cache_(std::move(package), budget_bytes),
      settings_(settings),
      renderer_(width, height),
      tiling_(cache_.package().meta.common.tiling, cross, world),
      width_(width),
      height_(height) {
  const tileformat::PointMetadata& m = cache_.package().meta;
  const std::string path = cache_.package().reader->path();
  if (m.fields.size() > size_t(kMaxChartFields))
    throw InputError(path + ": " + std::to_string(m.fields.size()) + " fields; charts show up to " +
                     std::to_string(kMaxChartFields) + " (rebuild it with fewer --fields)");
  if (m.signed_values && needs_shares(settings_.kind))
    throw UsageError(std::string("--chart ") + kind_name(settings_.kind) + ": " + path +
                     " holds negative values (built with --signed), and " +
                     kind_name(settings_.kind) +
                     " charts show shares of a whole; use --chart bar or --chart column");
  style_ = read_chart_style(m.fields, settings_.style);
  if (settings_.style) {
    std::error_code ec;
    style_time_ = std::filesystem::last_write_time(*settings_.style, ec);
  }
  roots_ = cache_.package().reader->tile_ids(m.common.min_zoom);
  if (settings_.heatmap)
    heat_style_ = heatmap_style(settings_.heat_opacity, settings_.heat_colormap);
  if (settings_.heatmap && settings_.heat_field != "count") {
    const auto f = std::find(m.fields.begin(), m.fields.end(), settings_.heat_field);
    if (f == m.fields.end()) {
      std::string names;
      for (const std::string& n : m.fields)
        names += (names.empty() ? "" : ", ") + n;
      throw UsageError("--heatmap " + settings_.heat_field + ": " + path + " has no such field (" +
                       names + "; or count)");
    }
    heat_field_ = static_cast<int>(f - m.fields.begin());
  }
  if (!is_url(path)) labels_ = std::make_unique<tileformat::PackageReader>(path);
}

ChartLayer::~ChartLayer() = default;

void ChartLayer::next_kind() {
  const ChartKind order[4] = {ChartKind::kPie, ChartKind::kBar, ChartKind::kStacked,
                              ChartKind::kColumn};
  int i = 0;
  while (order[i] != settings_.kind)
    ++i;
  do {
    i = (i + 1) % 4;
  } while (cache_.package().meta.signed_values && needs_shares(order[i]));
  settings_.kind = order[i];
  dirty_ = true;
}

bool ChartLayer::reload_style(bool always) {
  if (!settings_.style) return false;
  std::error_code ec;
  const auto t = std::filesystem::last_write_time(*settings_.style, ec);
  if (ec || (!always && t == style_time_)) return false;
  style_time_ = t;
  try {
    style_ = read_chart_style(cache_.package().meta.fields, settings_.style);
    dirty_ = true;
    return true;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "globe-view: %s (keeping the current chart style)\n", e.what());
    return false;
  }
}

std::vector<ChartLayer::Mark> ChartLayer::marks() const {
  std::vector<Mark> out;
  if (settings_.heatmap) return out;
  out.reserve(instances_.size());
  for (const ChartInstance& c : instances_) {
    const float r = settings_.kind == ChartKind::kPie ? 0.5f * c.params[0]
                                                      : 0.5f * static_cast<float>(style_.max_px);
    out.push_back({{c.key[0], c.key[1]}, {c.frac[0], c.frac[1]}, r});
  }
  return out;
}

void ChartLayer::build(const std::vector<TileId>& tiles, const View& view,
                       const WorldFrame& world) {
  const tileformat::PointMetadata& m = cache_.package().meta;
  std::unordered_map<int, const tileformat::PointZoomStats*> stats;
  for (const tileformat::PointZoomStats& z : m.zooms)
    stats[z.zoom] = &z;
  instances_.clear();
  places_.clear();
  const int fields = static_cast<int>(m.fields.size());
  for (const TileId& id : tiles) {
    const tileformat::PointTile* t = cache_.get(id);
    auto zs = stats.find(id.z);
    if (!t || zs == stats.end()) continue;
    const double max_total = std::max(zs->second->max_total, 1e-30);
    const double max_value = std::max(zs->second->max_value, 1e-30);
    // The tile's edge in world units, at its centre.
    const double keys =
        glm::length(tiling_.tile_to_key(id, 1, 0.5) - tiling_.tile_to_key(id, 0, 0.5));
    const double tile_world = keys * world.crs_per_key() * world.metres_per_crs_x();
    for (uint32_t i = 0; i < t->places.size(); ++i) {
      const tileformat::Place& pl = t->places[i];
      ChartInstance c{};
      const glm::dvec2 k =
          tiling_.tile_to_key(id, double(pl.at.x) / t->extent, double(pl.at.y) / t->extent);
      const double kx = k.x, ky = k.y;
      c.key[0] = static_cast<int32_t>(std::floor(kx));
      c.key[1] = static_cast<int32_t>(std::floor(ky));
      c.frac[0] = static_cast<float>(kx - std::floor(kx));
      c.frac[1] = static_cast<float>(ky - std::floor(ky));
      double total = 0, shares = 0;
      for (int f = 0; f < fields; ++f) {
        c.values[f] = t->value(i, static_cast<uint32_t>(f));
        total += std::abs(c.values[f]);
        shares += std::max(c.values[f], 0.0f);
      }
      if (total <= 0) continue;  // nothing to draw
      const double bar_px = std::clamp(std::round(style_.max_px * 0.8 / fields), 3.0, 24.0);
      switch (settings_.kind) {
        case ChartKind::kPie:
          if (shares <= 0) continue;
          c.params[0] = static_cast<float>(std::clamp(style_.max_px * std::sqrt(total / max_total),
                                                      style_.min_px, style_.max_px));
          break;
        case ChartKind::kBar:
          c.params[1] = static_cast<float>(style_.max_px / max_value);
          c.params[2] = static_cast<float>(bar_px);
          break;
        case ChartKind::kStacked:
          c.params[1] = static_cast<float>(style_.max_px / max_total);
          c.params[2] = static_cast<float>(std::clamp(style_.max_px / 3, 6.0, 24.0));
          break;
        case ChartKind::kColumn:
          c.params[0] = static_cast<float>(tile_world * bar_px / kTilePx);
          c.params[1] = static_cast<float>(tile_world * style_.column_px / kTilePx / max_value);
          break;
      }
      instances_.push_back(c);
      places_.push_back({id, i});
    }
  }
  if (settings_.kind != ChartKind::kColumn) sort_back_to_front(view, world);
  thinned_ = 0;
  if (settings_.thinning == ChartThinning::kOn) thin(view, world);
  for (size_t i = 0; i < instances_.size(); ++i)
    instances_[i].pick = static_cast<uint32_t>(i + 1);
  renderer_.set_instances(instances_);
}

void ChartLayer::sort_back_to_front(const View& view, const WorldFrame& world) {
  // Blended sprites are drawn in order: the farthest first, so nearer charts
  // cover farther ones (anchors at sea level; columns use the depth buffer).
  std::vector<std::pair<double, size_t>> order(instances_.size());
  for (size_t i = 0; i < instances_.size(); ++i) {
    const ChartInstance& c = instances_[i];
    const glm::dvec3 p =
        world.key_to_world(c.key[0] + c.frac[0], c.key[1] + c.frac[1], 0, view.origin);
    order[i] = {glm::dot(p - view.eye, p - view.eye), i};
  }
  std::stable_sort(order.begin(), order.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<ChartInstance> sorted(instances_.size());
  std::vector<PlaceRef> places(instances_.size());
  for (size_t k = 0; k < order.size(); ++k) {
    sorted[k] = instances_[order[k].second];
    places[k] = places_[order[k].second];
  }
  instances_ = std::move(sorted);
  places_ = std::move(places);
}

void ChartLayer::thin(const View& view, const WorldFrame& world) {
  // Screen discs of the charts (anchors at sea level), the largest placed
  // first; a chart whose centre falls inside a placed one's disc is dropped.
  struct Disc {
    double x, y, r;
    size_t index;
  };
  std::vector<Disc> discs;
  for (size_t i = 0; i < instances_.size(); ++i) {
    const ChartInstance& c = instances_[i];
    const glm::dvec4 p =
        view.proj * view.view *
        glm::dvec4(world.key_to_world(c.key[0] + c.frac[0], c.key[1] + c.frac[1], 0, view.origin),
                   1);
    if (p.w <= 0) continue;
    double r = 0.5 * c.params[0];
    if (settings_.kind != ChartKind::kPie) r = 0.5 * style_.max_px;
    discs.push_back(
        {(p.x / p.w * 0.5 + 0.5) * view.width, (p.y / p.w * 0.5 + 0.5) * view.height, r, i});
  }
  std::stable_sort(discs.begin(), discs.end(),
                   [](const Disc& a, const Disc& b) { return a.r > b.r; });
  const double cell = std::max(8.0, style_.max_px);
  std::unordered_map<int64_t, std::vector<size_t>> grid;  // cell -> placed discs
  std::vector<char> keep(instances_.size(), 0);
  std::vector<Disc> placed;
  for (const Disc& d : discs) {
    const int64_t cx = static_cast<int64_t>(std::floor(d.x / cell)),
                  cy = static_cast<int64_t>(std::floor(d.y / cell));
    bool covered = false;
    for (int64_t dy = -1; dy <= 1 && !covered; ++dy)
      for (int64_t dx = -1; dx <= 1 && !covered; ++dx) {
        auto it = grid.find((cx + dx) * 1000003 + (cy + dy));
        if (it == grid.end()) continue;
        for (size_t k : it->second)
          covered = covered || std::hypot(d.x - placed[k].x, d.y - placed[k].y) < placed[k].r;
      }
    if (covered) continue;
    grid[cx * 1000003 + cy].push_back(placed.size());
    placed.push_back(d);
    keep[d.index] = 1;
  }
  std::vector<ChartInstance> kept;
  std::vector<PlaceRef> kept_places;
  for (size_t i = 0; i < instances_.size(); ++i)
    if (keep[i]) {
      kept.push_back(instances_[i]);
      kept_places.push_back(places_[i]);
    }
  thinned_ = instances_.size() - kept.size();
  instances_ = std::move(kept);
  places_ = std::move(kept_places);
}

void ChartLayer::queue_legend() {
  if (!style_.legend) return;
  const tileformat::PointMetadata& m = cache_.package().meta;
  const float pad = 8, row = 20, swatch = 14;
  float width = 0;
  for (const std::string& f : m.fields)
    width = std::max(width, overlay_.text_width(f));
  const float w = pad * 3 + swatch + width, h = pad * 2 + row * float(m.fields.size()) - 6;
  const float x = 10, y = 10;
  overlay_.rect(x - 1, y - 1, w + 2, h + 2, {0.2f, 0.2f, 0.2f, 0.9f});
  overlay_.rect(x, y, w, h, {1, 1, 1, 0.88f});
  for (size_t i = 0; i < m.fields.size(); ++i) {
    const float ry = y + pad + row * float(i);
    overlay_.rect(x + pad, ry, swatch, swatch, hex_rgba(style_.colors[i]));
    overlay_.text(x + pad * 2 + swatch, ry, m.fields[i], {0.1f, 0.1f, 0.1f, 1});
  }
}

double ChartLayer::draw(const LayerPass& pass) {
  const GLuint input_fbo = pass.below_fbo;
  const GBuffer& g = pass.g;
  const View& view = pass.view;
  const WorldFrame& world = pass.world;
  const TerrainRenderer& terrain = pass.terrain;
  const TerrainHeights& heights = pass.heights;
  const double exaggeration = pass.shading.exaggeration;
  const Loading loading = pass.loading;
  const double az = pass.shading.sun_azimuth_deg * std::numbers::pi / 180,
               alt = pass.shading.sun_altitude_deg * std::numbers::pi / 180;
  const glm::vec3 sun(std::sin(az) * std::cos(alt), std::cos(az) * std::cos(alt), std::sin(alt));
  const tileformat::PointMetadata& m = cache_.package().meta;
  PointTileSelection sel;
  sel.roots = roots_;
  sel.max_zoom = m.common.max_zoom;
  sel.exists = [this](TileId id) { return cache_.exists(id); };
  sel.tiling = &tiling_;
  // A heatmap sums places: one zoom finer than charts, so merged places
  // stand closer to their sources.
  if (settings_.heatmap) sel.refine_px /= 2;
  std::vector<TileId> tiles;
  for (;;) {
    // The frame's tiles are marked used before loaded ones come in, so
    // making room for those never evicts a tile this frame draws.
    cache_.begin_frame();
    tiles = stand_in_tiles(
        select_point_tiles(sel, view, world), m.common.min_zoom, m.common.max_zoom,
        [this](TileId id) { return cache_.exists(id); },
        [this](TileId id) { return cache_.broken(id); });
    for (const TileId& id : tiles)
      cache_.get(id);
    cache_.flush_requests();
    if (cache_.take_loaded() > 0) dirty_ = true;  // tiles the instances lack may have come
    bool missing = false, broken = false;
    for (const TileId& id : tiles) {
      missing = missing || cache_.loading(id);
      broken = broken || cache_.broken(id);  // found broken now: select its stand-ins
    }
    if (loading == Loading::kAsReady || (!missing && !broken)) break;
    if (missing) cache_.wait_for_loader();
  }
  if (settings_.heatmap) {  // ground points move with the view origin: every frame
    build_heat(tiles, view, world);
    drawn_ = tiles;
    HeatmapStyle hs = heat_style_;
    hs.margin_world = static_cast<float>(heights.relief_world);
    return renderer_.draw_heatmap(input_fbo, g, view, world, terrain, heights, hs, exaggeration);
  }
  if (dirty_ || tiles != drawn_ || settings_.thinning == ChartThinning::kOn) {
    build(tiles, view, world);
    drawn_ = tiles;
    dirty_ = false;
  }
  ChartDrawStyle ds;
  ds.kind = settings_.kind;
  ds.depth = settings_.depth;
  ds.fields = static_cast<int>(m.fields.size());
  for (size_t i = 0; i < m.fields.size(); ++i)
    ds.colors[i] = hex_rgba(style_.colors[i]);
  const glm::vec4 outline = hex_rgba(style_.outline);
  ds.outline = {outline.r, outline.g, outline.b, static_cast<float>(style_.outline_px)};
  ds.opacity = static_cast<float>(style_.opacity);
  const double ms =
      renderer_.draw(input_fbo, g, view, world, terrain, heights, ds, exaggeration, sun);
  queue_legend();
  overlay_.draw(renderer_.output_fbo(), width_, height_);
  return ms;
}

void ChartLayer::build_heat(const std::vector<TileId>& tiles, const View& view,
                            const WorldFrame& world) {
  const tileformat::PointMetadata& m = cache_.package().meta;
  const bool mean = m.aggregate == tileformat::PointAggregate::kMean;
  const HeatFrame frame(view, world);
  const HeatRadius radius{settings_.heat_radius, settings_.heat_radius_m};
  ground_per_m_ = frame.ground_per_m();
  instances_.clear();
  places_.clear();
  for (const TileId& id : tiles) {
    const tileformat::PointTile* tile = cache_.get(id);
    if (!tile) continue;
    for (uint32_t i = 0; i < tile->places.size(); ++i) {
      const tileformat::Place& pl = tile->places[i];
      const double weight =
          heat_field_ < 0 ? double(pl.count)
                          : tile->value(i, uint32_t(heat_field_)) * (mean ? double(pl.count) : 1.0);
      if (!(weight > 0)) continue;  // a density of what is there: no negative mass
      const glm::dvec2 k =
          tiling_.tile_to_key(id, double(pl.at.x) / tile->extent, double(pl.at.y) / tile->extent);
      instances_.push_back(frame.instance(k, weight, radius));
      places_.push_back({id, i});
    }
  }
  renderer_.set_instances(instances_);
}

std::string ChartLayer::describe(int x, int y) {
  if (settings_.heatmap) {
    // The density there, per square kilometre of ground.
    char buf[64];
    std::snprintf(buf, sizeof buf, "heatmap: %.6g per km2",
                  renderer_.density_at(x, y) * ground_per_m_ * ground_per_m_ * 1e6);
    return buf;
  }
  const uint32_t pick = renderer_.pick(x, y);
  if (pick == 0 || pick > places_.size()) return "";
  const PlaceRef& ref = places_[pick - 1];
  const tileformat::PointTile* t = cache_.get(ref.tile);
  if (!t) return "";
  const tileformat::PointMetadata& m = cache_.package().meta;
  const tileformat::Place& pl = t->places[ref.index];
  std::string label = "place " + std::to_string(pl.id);
  try {
    if (!labels_) return label;  // a remote source: no features table
    tileformat::FeatureTableReader features(*labels_);
    if (auto f = features.get(static_cast<int64_t>(pl.id)); f && !m.label_field.empty()) {
      const tileformat::JsonValue props = tileformat::JsonValue::parse(f->properties);
      if (const tileformat::JsonValue* v = props.find(m.label_field))
        label = v->is_string() ? v->string() : v->is_number() ? number_text(v->number()) : label;
    }
  } catch (const std::exception&) {
    // A label is a courtesy: without one the place keeps its id.
  }
  std::ostringstream o;
  o << label;
  if (pl.count > 1) o << " and " << pl.count - 1 << " more places";
  o << ":";
  for (size_t f = 0; f < m.fields.size(); ++f)
    o << (f ? ", " : " ") << m.fields[f] << " " << number_text(t->value(ref.index, uint32_t(f)));
  if (m.aggregate == tileformat::PointAggregate::kMean && pl.count > 1) o << " (means)";
  return o.str();
}

std::string ChartLayer::pick_json(int x, int y) {
  if (settings_.heatmap) return "null";
  const uint32_t pick = renderer_.pick(x, y);
  if (pick == 0 || pick > places_.size()) return "null";
  const PlaceRef& ref = places_[pick - 1];
  const tileformat::PointTile* t = cache_.get(ref.tile);
  if (!t) return "null";
  const tileformat::PointMetadata& m = cache_.package().meta;
  const tileformat::Place& pl = t->places[ref.index];
  std::ostringstream o;
  o << "{\"id\": " << pl.id << ", \"count\": " << pl.count << ", \"values\": {";
  for (size_t f = 0; f < m.fields.size(); ++f)
    o << (f ? ", " : "") << "\"" << tileformat::json_escape(m.fields[f])
      << "\": " << number_text(t->value(ref.index, uint32_t(f)));
  o << "}}";
  return o.str();
}

ChartLayerStats ChartLayer::stats() const {
  return {cache_.stats(), drawn_.size(), instances_.size(), thinned_};
}

std::string ChartLayer::stats_json(double ms) const {
  const ChartLayerStats cs = stats();
  char text[512];
  std::snprintf(
      text, sizeof text,
      ", \"charts_ms\": %.3f, \"chart_tiles\": %zu, \"charts\": %zu, \"charts_thinned\": %zu, "
      "\"point_tiles_loaded\": %llu, \"point_bytes\": %llu, \"broken_point_tiles\": %llu",
      ms, cs.tiles, cs.charts, cs.thinned, static_cast<unsigned long long>(cs.cache.loaded),
      static_cast<unsigned long long>(cs.cache.resident_bytes),
      static_cast<unsigned long long>(cs.cache.broken));
  return text;
}

}  // namespace globe::viewer
