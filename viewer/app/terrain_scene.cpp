// One viewer session's frame sequence (see terrain_scene.hpp).
#include "app/terrain_scene.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

#include "app/analysis_overlay.hpp"
#include "app/package_set.hpp"
#include "render/readback.hpp"
#include "runtime/area_package.hpp"
#include "runtime/errors.hpp"
#include "runtime/line_package.hpp"
#include "runtime/point_package.hpp"
#include "runtime/terrain_package.hpp"
#include "tileformat/package.hpp"

namespace globe::viewer {

namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

tileformat::Bounds data_bounds_crs(const TerrainPackage& p, const WorldFrame& world) {
  // MBTiles "bounds" is lon/lat; project its corners and edge midpoints.
  if (!p.meta.common.has_bounds) return p.tiling.extent();
  const tileformat::Bounds& ll = p.meta.common.lonlat;
  const double v[4] = {ll.min_x, ll.min_y, ll.max_x, ll.max_y};
  tileformat::Bounds b{1e300, 1e300, -1e300, -1e300};
  for (double fx : {0.0, 0.5, 1.0})
    for (double fy : {0.0, 0.5, 1.0}) {
      const glm::dvec2 c =
          world.lonlat_to_crs(v[0] + fx * (v[2] - v[0]), v[1] + fy * (v[3] - v[1]));
      b.min_x = std::min(b.min_x, c.x), b.max_x = std::max(b.max_x, c.x);
      b.min_y = std::min(b.min_y, c.y), b.max_y = std::max(b.max_y, c.y);
    }
  return b;
}

}  // namespace

TerrainScene::TerrainScene(const ViewerSettings& settings) : settings_(settings) {
  ramp_ = std::make_unique<ElevationRamp>(settings_.shading);
  PackageSet set = sort_packages(settings_.packages);
  if (set.terrain.empty()) {
    base_ = std::make_unique<FlatBase>(set);
    set.terrain = base_->path();
    std::fprintf(stderr,
                 "globe-view: no terrain given; drawing over zero heights (the ellipsoid on the "
                 "globe, a flat base on the map frame)\n");
  }
  const std::string& path = set.terrain;
  TerrainPackage package = open_terrain_package(path);
  std::optional<LinePackage> lines;
  CrsCross line_cross = CrsCross::kSame, point_cross = CrsCross::kSame;
  if (set.lines && settings_.lines) {
    lines = open_line_package(*set.lines);
    line_cross = layer_cross(package.tiling, path, lines->tiling, *set.lines);
    if (line_cross != CrsCross::kSame && settings_.line_mode != LineMode::kDeferred)
      throw UsageError(*set.lines + " is tiled unlike the terrain (" +
                       tileformat::scheme_name(lines->tiling.scheme) + " over " +
                       tileformat::scheme_name(package.tiling.scheme) +
                       "): --lines geometry and --bundles 3d need the terrain's tiling; drop "
                       "them to draw the lines per pixel, or rebuild the lines with --tiling " +
                       tileformat::scheme_name(package.tiling.scheme));
  } else if (settings_.style) {
    throw UsageError("--style styles lines; give a line package too");
  }
  std::optional<AreaPackage> areas;
  CrsCross area_cross = CrsCross::kSame;
  if (set.areas) {
    areas = open_area_package(*set.areas);
    area_cross = layer_cross(package.tiling, path, areas->meta.common.tiling, *set.areas);
  }
  std::optional<PointPackage> points;
  if (set.points) {
    points = open_point_package(*set.points);
    point_cross = layer_cross(package.tiling, path, points->meta.common.tiling, *set.points);
  } else if (settings_.charts_given && !(settings_.charts.heatmap && set.lines)) {
    throw UsageError(
        "--chart, --chart-style, --chart-depth and --chart-thinning draw charts; give "
        "a point package too (globe-vectorize points)");
  }
  if (set.images.empty() && settings_.imagery_unlit)
    throw UsageError("--shading imagery: give an image package too");
  if (set.images.empty() && !settings_.image_opacity.empty())
    throw UsageError("--image-opacity: give an image package too");
  // Each layer holds its share of the budget (LineLayer::kBudgetShare …);
  // the terrain's blocks hold the rest.
  const uint64_t budget = settings_.cache_mb << 20;
  auto share = [&](bool present, double s) { return present ? uint64_t(budget * s) : 0; };
  const uint64_t line_budget = share(lines.has_value(), LineLayer::kBudgetShare);
  const uint64_t image_budget = share(!set.images.empty(), ImageLayers::kBudgetShare);
  const uint64_t point_budget = share(points.has_value(), ChartLayer::kBudgetShare);
  const uint64_t area_budget = share(areas.has_value(), AreaLayer::kBudgetShare);
  if (package.max_zoom > 21)
    throw InputError(path + ": maxzoom " + std::to_string(package.max_zoom) +
                     " is deeper than the viewer's integer vertex frame supports (21)");
  if (!settings_.globe) {
    const tileformat::Bounds& ll = package.meta.common.lonlat;
    const bool wide = package.meta.common.has_bounds &&
                      (std::max(ll.width(), ll.height()) > kGlobeDefaultSpanDeg);
    settings_.globe = package.tiling.scheme != tileformat::Scheme::kLocal && wide &&
                      !(lines && settings_.line_mode == LineMode::kGeometry);
  }
  if (*settings_.globe && lines && settings_.line_mode == LineMode::kGeometry)
    throw UsageError(
        "--globe: --lines geometry (the baseline of draped quads) draws on the flat frame only; "
        "the globe draws lines per pixel (--lines deferred, the default)");
  world_ = std::make_unique<WorldFrame>(package.tiling, package.block_size - 1, package.max_zoom,
                                        *settings_.globe ? Surface::kGlobe : Surface::kFlat);
  std::optional<AnalysisSource> analysis;
  analysis_path_ = set.analysis;
  if (set.analysis) {
    AnalysisOverlay o = open_analysis_overlay(*set.analysis, package, path);
    analysis_layers_ = o.layers;
    analysis = std::move(o.source);
  }
  if (const std::string e = shading_problem(settings_.shading); !e.empty()) throw UsageError(e);
  ground_ = std::make_unique<GroundProbe>(path);
  // The relief stretch is the default look; --exaggeration given is the
  // user's own choice of relief.
  auto_relief_ = !settings_.shading.exaggeration_given;
  cache_ = std::make_unique<BlockCache>(
      path, std::move(package), budget - line_budget - image_budget - point_budget - area_budget,
      std::move(analysis));
  selector_ = std::make_unique<PatchSelector>(cache_->package());
  if (selector_->root_tiles().empty())
    throw InputError(path + ": no tiles at minzoom " + std::to_string(cache_->package().min_zoom) +
                     "; the package is empty or its metadata is wrong");
  make_renderer(path, set.analysis);
  // The layers, bottom first: imagery, areas, lines, charts.
  auto add = [this](auto layer) {
    auto* typed = layer.get();
    layers_.push_back(std::move(layer));
    return typed;
  };
  if (!set.images.empty())
    images_ = add(std::make_unique<ImageLayers>(
        set.images, settings_.image_opacity, *world_,
        cache_->package().meta.common.has_bounds ? &cache_->package().meta.common.lonlat : nullptr,
        image_budget, settings_.width, settings_.height));
  if (areas)
    areas_ = add(std::make_unique<AreaLayer>(*set.areas, std::move(*areas), settings_.area_opacity,
                                             area_budget, settings_.width, settings_.height,
                                             area_cross));
  if (lines) {
    lines_ = add(std::make_unique<LineLayer>(*set.lines, std::move(*lines), settings_.style,
                                             settings_.line_mode, line_budget, settings_.width,
                                             settings_.height, line_cross));
    if (settings_.charts.heatmap && !points)  // a heatmap of the lines
      lines_->enable_heatmap(
          {settings_.charts.heat_radius, settings_.charts.heat_radius_m},
          heatmap_style(settings_.charts.heat_opacity, settings_.charts.heat_colormap), *world_);
  }
  if (points)
    charts_ =
        add(std::make_unique<ChartLayer>(std::move(*points), settings_.charts, point_budget,
                                         settings_.width, settings_.height, point_cross, *world_));
  // Names last, over everything.
  std::vector<std::string> vector_packages;
  for (const std::optional<std::string>& p : {set.areas, set.lines, set.points})
    if (p) vector_packages.push_back(*p);
  if (!vector_packages.empty() && (settings_.labels.enabled || settings_.labels_json)) {
    std::unique_ptr<LabelLayer> labels;
    try {
      labels = std::make_unique<LabelLayer>(vector_packages, settings_.labels, *world_,
                                            settings_.width, settings_.height);
    } catch (const InputError& e) {
      // No fonts installed: the map without its names, not no map (a
      // --label-font the user named that cannot be read stays an error).
      if (!settings_.labels.font.empty() || std::string(e.what()).find("text:") != 0) throw;
      std::fprintf(stderr, "globe-view: %s; drawing no labels\n", e.what());
    }
    if (!labels) return;
    labels->set_charts(charts_);
    std::vector<const SceneLayer*> below;
    for (const auto& l : layers_)
      below.push_back(l.get());
    labels->set_layers_below(std::move(below));
    if (labels->has_labels()) labels_ = add(std::move(labels));
  }
}

TerrainScene::~TerrainScene() = default;

void TerrainScene::make_renderer(const std::string& path,
                                 const std::optional<std::string>& analysis) {
  renderer_ =
      std::make_unique<TerrainRenderer>(cache_->package().block_size, cache_->package().lattice,
                                        static_cast<int>(cache_->slot_count()), settings_.width,
                                        settings_.height, analysis.has_value());
  // Blocks a remote source's tiles were made into are not nested: skirts
  // (block_synthesizer.hpp), a twentieth of a patch's leg deep.
  if (cache_->package().reader->meta("globe:synthesized")) renderer_->set_skirts(0.05f);
  auto holds = [&](tileformat::AnalysisLayer l) {
    return std::find(analysis_layers_.begin(), analysis_layers_.end(), l) != analysis_layers_.end();
  };
  renderer_->set_gradient_from_layers(holds(tileformat::AnalysisLayer::kSlope) &&
                                      holds(tileformat::AnalysisLayer::kAspect));
  ranges_ = measure_data_ranges(path, analysis,
                                [this](tileformat::TileId id) { return block_spacing_m(id); });
  renderer_->set_data_ranges(static_cast<float>(ranges_.slope_top_deg),
                             static_cast<float>(ranges_.sky_low));
  if (world_->globe()) {
    const TerrainPackage& p = cache_->package();
    const tileformat::Bounds ll =
        p.meta.common.has_bounds ? p.meta.common.lonlat : p.tiling.lonlat_limits();
    double finest = p.tiling.sample_spacing(p.max_zoom, p.block_size - 1);
    if (p.tiling.scheme == tileformat::Scheme::kWebMercator) finest /= 111320.0;  // ~degrees
    caps_ = std::make_unique<PolarCaps>(*world_, ll, finest, p.meta.fill_height);
  }
}

TerrainHeights TerrainScene::terrain_heights(const View& view) {
  const TerrainPackage& p = package();
  TerrainHeights h{renderer_->heights_texture(), cache_->resident_slots(), p.min_zoom, p.max_zoom,
                   p.block_size};
  h.frame = renderer_.get();
  h.lift_m = settings_.lift_m ? *settings_.lift_m : 0.03 * glm::length(view.eye);
  h.error_px = settings_.max_error_px;
  h.relief_world = (selector_->top_height_m(*cache_) - selector_->bottom_height_m(*cache_)) *
                   world_->height_scale() * settings_.shading.exaggeration;
  return h;
}

std::string TerrainScene::shading_problem(const ShadingSettings& shading) const {
  return shading_needs(shading, analysis_path_, analysis_layers_);
}

void TerrainScene::resize(int width, int height) {
  renderer_->resize(width, height);
  for (const auto& layer : layers_)
    layer->resize(width, height);
}

GLuint TerrainScene::output_fbo() const {
  return layers_.empty() ? renderer_->gbuffer().fbo : layers_.back()->output_fbo();
}

bool TerrainScene::loading() {
  if (cache_->loader_busy()) return true;
  for (const auto& layer : layers_)
    if (layer->loading()) return true;
  return false;
}

std::optional<glm::dvec3> TerrainScene::ground_at(const View& view, int x, int y) const {
  const GBuffer& g = renderer_->gbuffer();
  if (x < 0 || y < 0 || x >= g.width || y >= g.height) return std::nullopt;
  if (read_position(g.fbo, x, y, g.height).w == 0) return std::nullopt;
  // Ground metres from the view origin (x east, y north), and the height.
  const glm::vec4 ground = read_rgba32f(g.fbo, 3, x, y, g.height);
  const glm::vec4 dy = read_rgba32f(g.fbo, 4, x, y, g.height);
  const glm::dvec2 o = world_->key_to_crs(double(view.origin.x), double(view.origin.y));
  try {
    const glm::dvec2 ll = world_->crs_to_lonlat(o.x + ground.x / world_->ground_per_crs_x(),
                                                o.y + ground.y / world_->ground_per_crs_y());
    return glm::dvec3(ll.x, ll.y, dy.z);
  } catch (const std::exception&) {
    return std::nullopt;  // past what the CRS can say in degrees
  }
}

SceneLayer* TerrainScene::picking_layer() {
  for (auto it = layers_.rbegin(); it != layers_.rend(); ++it)
    if ((*it)->picks()) return it->get();
  return nullptr;
}

std::vector<uint8_t> TerrainScene::read_pixels() const {
  return read_rgba(output_fbo(), renderer_->width(), renderer_->height());
}

void TerrainScene::upload_loaded() {
  for (const LoadedBlock& b : cache_->take_loaded()) {
    if (b.id.z == ramp_zoom_) {
      ramp_->add_samples(b);
      ramp_level_.push_back(b.id);
    }
    const TerrainPackage& p = cache_->package();
    if (edges_.add_samples(
            b, p.tiling.sample_spacing(b.id.z, p.block_size - 1) * world_->metres_per_crs_x()))
      renderer_->set_edge_scales(edges_.scales());
    if (auto_relief_) {
      const auto [sx, sy] = block_spacing_m(b.id);
      if (relief_.add_samples(b, sx, sy)) renderer_->set_relief_stretches(relief_.stretches());
    }
    // Flow: the largest river loaded so far (coarser zooms keep the largest
    // area of their footprint, so the first blocks already hold it) and eight
    // doublings below it.
    float largest = kNoFlow;
    for (size_t i = 0; i < b.flow.size(); i += kFlowTexel)
      largest = std::max(largest, b.flow[i]);
    if (largest > flow_largest_) {
      flow_largest_ = largest;
      renderer_->set_flow_range(largest - 8, largest);
      if (ramp_->finished() && ramp_mode_ == Shading::kFlow) apply_ramp();
    }
    renderer_->upload(b);
  }
}

void TerrainScene::load_now(const std::vector<tileformat::TileId>& tiles) {
  cache_->begin_frame();
  for (const tileformat::TileId& id : tiles)
    cache_->request(id, 0);
  cache_->flush_requests();
  while (cache_->loader_busy()) {
    cache_->wait_for_loader();
    upload_loaded();
  }
  upload_loaded();
}

void TerrainScene::sample_heights() {
  // The ramp's heights come from the coarsest zoom with enough valid
  // samples: a small dataset covers one sample of its root block, so go
  // down (at most 64 blocks a zoom) until the data has 64 k samples.
  constexpr size_t kEnough = 65536, kMaxBlocks = 64;
  while (ramp_->sample_count() < kEnough && ramp_zoom_ < cache_->package().max_zoom) {
    std::vector<tileformat::TileId> next;
    for (const tileformat::TileId& id : ramp_level_)
      for (const tileformat::TileId& c : id.children())
        if (cache_->state(c) != BlockState::kAbsent) next.push_back(c);
    if (next.empty() || next.size() > kMaxBlocks) break;
    ramp_->clear_samples();
    ramp_level_.clear();
    ++ramp_zoom_;
    load_now(next);
  }
  ramp_zoom_ = -1;
  ramp_->finish();
  apply_ramp();
}

CameraPose TerrainScene::initial_pose() {
  ramp_zoom_ = cache_->package().min_zoom;
  load_now(selector_->root_tiles());
  if (!ramp_->finished()) sample_heights();
  const double top = selector_->top_height_m(*cache_);
  if (settings_.camera) return *settings_.camera;
  if (!settings_.camera_path.empty()) return settings_.camera_path.front();
  CameraPose pose = fit_pose(data_bounds_crs(package(), *world_), *world_, settings_.width,
                             settings_.height, top);
  pose.fov_y_deg = settings_.fov_y_deg;
  return pose;
}

View TerrainScene::make(const CameraPose& pose) {
  const double zs = world_->height_scale() * settings_.shading.exaggeration;
  world_->set_view_latitude(pose.lat);
  return make_view(pose, *world_, renderer_->width(), renderer_->height(),
                   selector_->top_height_m(*cache_) * zs, selector_->bottom_height_m(*cache_) * zs);
}

std::pair<double, double> TerrainScene::block_spacing_m(tileformat::TileId id) const {
  const TerrainPackage& p = package();
  const double spacing = p.tiling.sample_spacing(id.z, p.block_size - 1);
  const tileformat::Bounds b = p.tiling.tile_bounds(id);
  const glm::dvec2 key = world_->crs_to_key((b.min_x + b.max_x) / 2, (b.min_y + b.max_y) / 2);
  const double cos_lat = std::cos(world_->key_to_latlon(key.x, key.y).x);
  switch (p.tiling.scheme) {
    case tileformat::Scheme::kGeodetic:  // degrees
      return {spacing * 111320 * cos_lat, spacing * 111320};
    case tileformat::Scheme::kWebMercator:  // metres at the equator
      return {spacing * cos_lat, spacing * cos_lat};
    case tileformat::Scheme::kLocal:
      break;
  }
  return {spacing, spacing};
}

void TerrainScene::find_neighbours(std::vector<Patch>& patches) {
  const tileformat::Tiling& t = package().tiling;
  for (Patch& p : patches) {
    const tileformat::TileId id = p.tile;
    const int64_t nx = int64_t(t.tiles_x(id.z)), ny = int64_t(t.tiles_y(id.z));
    const int64_t at[4][2] = {
        {id.x - 1, id.y}, {id.x + 1, id.y}, {id.x, id.y - 1}, {id.x, id.y + 1}};
    for (int k = 0; k < 4; ++k) {
      int64_t x = at[k][0];
      const int64_t y = at[k][1];
      if (t.wraps_x()) x = (x + nx) % nx;  // across the antimeridian
      if (x < 0 || x >= nx || y < 0 || y >= ny) continue;
      const ResidentBlock* b = cache_->use({id.z, uint32_t(x), uint32_t(y)});
      p.neighbours[k] = b ? b->slot : -1;
    }
  }
}

CameraPose TerrainScene::above_ground(const CameraPose& pose) {
  // The eye stays this far above the drawn ground (metres).
  constexpr double kClearanceM = 20;
  glm::dvec2 crs;
  try {
    crs = world_->lonlat_to_crs(pose.lon, pose.lat);
  } catch (const std::exception&) {
    return pose;  // outside the tiling (e.g. past web mercator's latitudes)
  }
  const std::optional<double> ground = ground_->height_at(crs.x, crs.y);
  const double lowest =
      ground ? *ground * settings_.shading.exaggeration + kClearanceM : pose.height_m;
  const bool raise = pose.height_m < lowest;
  if (raise && !raised_)
    std::fprintf(stderr,
                 "globe-view: the camera at %.0f m is below the ground under it (%.0f m above the "
                 "ellipsoid%s); drawn from %.0f m\n",
                 pose.height_m, *ground * settings_.shading.exaggeration,
                 settings_.shading.exaggeration != 1 ? ", exaggerated" : "", lowest);
  raised_ = raise;
  if (!raise) return pose;
  CameraPose p = pose;
  p.height_m = lowest;
  return p;
}

FrameResult TerrainScene::frame(const CameraPose& asked, Loading loading, Output output) {
  FrameResult f;
  f.pose = above_ground(asked);
  const CameraPose& pose = f.pose;
  SelectionSettings sel{settings_.max_error_px, settings_.shading.exaggeration, settings_.cull};
  for (int round = 0;; ++round) {
    cache_->begin_frame();
    upload_loaded();
    const auto t0 = std::chrono::steady_clock::now();
    f.view = make(pose);
    f.patches = selector_->select(f.view, *world_, *cache_, sel, &f.selection);
    f.select_ms = ms_since(t0);
    cache_->flush_requests();
    if (loading == Loading::kAsReady || !cache_->loader_busy() || round > 1000) break;
    cache_->wait_for_loader();
  }
  if (output == Output::kSelectOnly) return f;
  find_neighbours(f.patches);  // once, for the patches drawn
  if (ramp_->finished() && settings_.shading.mode != ramp_mode_) apply_ramp();
  f.terrain_ms = renderer_->draw(f.patches, f.view, *world_, settings_.shading).terrain_ms;
  if (caps_) {
    // Flat ground's hillshade, a little towards white: ice, plainly.
    const double sun_z = std::sin(settings_.shading.sun_altitude_deg * std::numbers::pi / 180);
    const float grey = static_cast<float>(0.12 + 0.88 * std::max(sun_z, 0.05));
    caps_->draw(renderer_->gbuffer(), f.view, *world_,
                glm::vec3(grey * 0.92f + 0.08f, grey * 0.94f + 0.06f, grey * 0.96f + 0.04f));
  }
  if (layers_.empty()) return f;  // terrain alone: no resident-block table to gather
  // Each layer draws over the image so far: the terrain's colour, then the
  // layer before's output.
  const TerrainHeights heights = terrain_heights(f.view);
  LayerPass pass{
      renderer_->gbuffer(), renderer_->gbuffer().fbo, f.view, *world_, *renderer_, heights,
      settings_.shading};
  std::tie(pass.height_lo, pass.height_hi) = ramp_->data_range();
  pass.imagery_unlit = settings_.imagery_unlit;
  pass.loading = loading;
  for (const auto& layer : layers_) {
    f.layer_ms.push_back(layer->draw(pass));
    pass.below_fbo = layer->output_fbo();
    pass.g.color = layer->output_texture();
  }
  return f;
}

}  // namespace globe::viewer
