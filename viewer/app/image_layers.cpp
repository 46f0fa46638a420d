// The image layers of one view (see image_layers.hpp).
#include "app/image_layers.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "camera/layer_tiling.hpp"
#include "camera/proj_crs.hpp"
#include "render/image_shaders.hpp"
#include "runtime/errors.hpp"

namespace globe::viewer {

namespace {

using tileformat::Bounds;
using tileformat::Scheme;

constexpr int kGridN = 129;  // samples per side of a kGrid mapping
// The image's footprint in the terrain's tiling CRS (densified bounds), cut
// to the terrain tiling's extent; empty if they do not meet.
Bounds footprint_in_terrain(const ImagePackage& img, const WorldFrame& world) {
  Bounds ll = img.meta.common.has_bounds ? img.meta.common.lonlat : img.tiling.lonlat_limits();
  const Bounds limits = world.tiling().lonlat_limits();
  ll = {std::max(ll.min_x, limits.min_x), std::max(ll.min_y, limits.min_y),
        std::min(ll.max_x, limits.max_x), std::min(ll.max_y, limits.max_y)};
  Bounds b{1e300, 1e300, -1e300, -1e300};
  constexpr int kSteps = 32;
  for (int i = 0; i <= kSteps; ++i)
    for (int j = 0; j <= kSteps; ++j) {
      if (i != 0 && i != kSteps && j != 0 && j != kSteps) continue;  // the boundary
      try {
        const glm::dvec2 c = world.lonlat_to_crs(ll.min_x + (ll.max_x - ll.min_x) * i / kSteps,
                                                 ll.min_y + (ll.max_y - ll.min_y) * j / kSteps);
        b = {std::min(b.min_x, c.x), std::min(b.min_y, c.y), std::max(b.max_x, c.x),
             std::max(b.max_y, c.y)};
      } catch (const std::runtime_error&) {
      }
    }
  const Bounds e = world.tiling().extent();
  return {std::max(b.min_x, e.min_x), std::max(b.min_y, e.min_y), std::min(b.max_x, e.max_x),
          std::min(b.max_y, e.max_y)};
}

// Whether two lon/lat boxes meet, longitudes taken modulo 360 (a box whose
// west is east of its east crosses the antimeridian).
bool lonlat_boxes_meet(const Bounds& a, const Bounds& b) {
  if (a.max_y < b.min_y || b.max_y < a.min_y) return false;
  const double aw = a.max_x >= a.min_x ? a.max_x - a.min_x : a.max_x + 360 - a.min_x;
  const double bw = b.max_x >= b.min_x ? b.max_x - b.min_x : b.max_x + 360 - b.min_x;
  if (aw >= 360 || bw >= 360) return true;
  // b's west edge, east of a's west edge by 0..360 degrees.
  const double d = std::fmod(std::fmod(b.min_x - a.min_x, 360.0) + 360.0, 360.0);
  return d <= aw || d + bw >= 360;
}

}  // namespace

ImageLayers::ImageLayers(const std::vector<std::string>& paths,
                         const std::vector<double>& opacities, const WorldFrame& world,
                         const tileformat::Bounds* terrain_lonlat, uint64_t budget_bytes, int width,
                         int height)
    : renderer_(width, height, kGridN) {
  if (paths.size() > size_t(shaders::kMaxImageLayers))
    throw UsageError(std::to_string(paths.size()) + " image packages; globe-view blends up to " +
                     std::to_string(shaders::kMaxImageLayers));
  const tileformat::Tiling& tt = world.tiling();
  GLint max_layers = 2048;
  gl::GetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
  for (size_t i = 0; i < paths.size(); ++i) {
    const std::string& path = paths[i];
    ImagePackage pkg = open_image_package(path);
    if (pkg.tile_size < 1 || (pkg.tile_size & (pkg.tile_size - 1)) != 0 || pkg.tile_size > 4096)
      throw InputError(path + ": tiles of " + std::to_string(pkg.tile_size) +
                       " px; globe-view drapes square power-of-two tiles up to 4096 px");
    const bool apart = terrain_lonlat && pkg.meta.common.has_bounds &&
                       !lonlat_boxes_meet(*terrain_lonlat, pkg.meta.common.lonlat);
    if (apart) {
      const Bounds& b = pkg.meta.common.lonlat;
      std::fprintf(stderr,
                   "globe-view: warning: %s: the image (lon %g..%g, lat %g..%g) does not overlap "
                   "the terrain; only the terrain is shown there\n",
                   path.c_str(), b.min_x, b.max_x, b.min_y, b.max_y);
    }
    Layer l;
    l.opacity = i < opacities.size() ? opacities[i] : (opacities.empty() ? 1.0 : opacities.back());
    const tileformat::Tiling& it = pkg.tiling;
    std::vector<float> grid;
    const CrsCross cross = crs_cross(tt, it);
    if (cross == CrsCross::kSame && (it.scheme != Scheme::kLocal || it.crs == tt.crs ||
                                     crs_equivalent(it.crs, path, tt.crs, "the terrain"))) {
      l.mode = ImageLayerFrame::kSameCrs;
    } else if (cross == CrsCross::kGeodeticToMercator || cross == CrsCross::kMercatorToGeodetic) {
      l.mode = static_cast<int>(cross);
    } else {
      l.mode = ImageLayerFrame::kGrid;
      const Bounds fp = footprint_in_terrain(pkg, world);
      if (!apart && !(fp.min_x < fp.max_x && fp.min_y < fp.max_y)) {
        std::fprintf(stderr,
                     "globe-view: warning: %s: the image does not overlap the terrain's tiling; "
                     "it is not drawn\n",
                     path.c_str());
      }
      l.grid_nw = {fp.min_x, fp.max_y};
      l.grid_cell = {std::max(fp.max_x - fp.min_x, 1e-9) / (kGridN - 1),
                     std::max(fp.max_y - fp.min_y, 1e-9) / (kGridN - 1)};
      ProjTransform to_image("EPSG:4326", it.crs, path);
      const double nan = std::numeric_limits<double>::quiet_NaN();
      std::vector<glm::dvec2> v(size_t(kGridN) * kGridN, glm::dvec2(nan));
      for (int r = 0; r < kGridN; ++r)
        for (int c = 0; c < kGridN; ++c) {
          try {
            glm::dvec2 ll = world.crs_to_lonlat(l.grid_nw.x + c * l.grid_cell.x,
                                                l.grid_nw.y - r * l.grid_cell.y);
            if (it.scheme == Scheme::kWebMercator)
              ll.y = std::clamp(ll.y, -kMaxMercatorLat, kMaxMercatorLat);
            if (to_image.transform(ll.x, ll.y)) v[size_t(r) * kGridN + c] = ll;
          } catch (const std::runtime_error&) {
          }
        }
      l.grid_anchor = v[size_t(kGridN / 2) * kGridN + kGridN / 2];
      if (!std::isfinite(l.grid_anchor.x)) l.grid_anchor = {it.origin_x, it.origin_y};
      grid.resize(v.size() * 2);
      for (size_t k = 0; k < v.size(); ++k) {
        // Points the image CRS cannot hold land far outside every tile.
        const bool ok = std::isfinite(v[k].x) && std::isfinite(v[k].y);
        grid[2 * k] = ok ? static_cast<float>(v[k].x - l.grid_anchor.x) : 1e30f;
        grid[2 * k + 1] = ok ? static_cast<float>(v[k].y - l.grid_anchor.y) : 1e30f;
      }
    }
    const uint64_t tile_bytes = uint64_t(pkg.tile_size) * pkg.tile_size * 4 * 4 / 3;
    const uint64_t share = budget_bytes / std::max<size_t>(paths.size(), 1);
    const int slots =
        static_cast<int>(std::clamp<uint64_t>(share / tile_bytes, 16, uint64_t(max_layers)));
    l.cache = std::make_unique<ImageCache>(path, std::move(pkg), slots);
    renderer_.add_layer(*l.cache, grid);
    layers_.push_back(std::move(l));
  }
}

ImageLayers::~ImageLayers() = default;

void ImageLayers::set_opacity(size_t i, double v) {
  layers_.at(i).opacity = std::clamp(v, 0.0, 1.0);
}

ImageLayerFrame ImageLayers::frame_of(const Layer& l, const View& view,
                                      const WorldFrame& world) const {
  const tileformat::Tiling& it = l.cache->package().tiling;
  const glm::dvec2 o = world.key_to_crs(double(view.origin.x), double(view.origin.y));
  ImageLayerFrame f;
  f.mode = l.mode;
  f.opacity = l.visible ? static_cast<float>(l.opacity) : 0.0f;
  glm::dvec2 anchor = o;  // image CRS point the shader's offsets start from
  if (l.mode == ImageLayerFrame::kGeodeticToMercator ||
      l.mode == ImageLayerFrame::kMercatorToGeodetic) {
    const CrossAnchor a = cross_anchor(static_cast<CrsCross>(l.mode), o);
    anchor = a.anchor;
    f.param = a.param;
  } else if (l.mode == ImageLayerFrame::kGrid) {
    anchor = l.grid_anchor;
    f.grid_org = {static_cast<float>((o.x - l.grid_nw.x) / l.grid_cell.x),
                  static_cast<float>((l.grid_nw.y - o.y) / l.grid_cell.y)};
    f.grid_inv_cell = {static_cast<float>(1 / l.grid_cell.x),
                       static_cast<float>(1 / l.grid_cell.y)};
  }
  f.ref_zoom = l.cache->package().max_zoom;
  const double size = it.tile_size(f.ref_zoom);
  const double tx = (anchor.x - it.origin_x) / size, ty = (it.origin_y - anchor.y) / size;
  const double bx = std::floor(tx), by = std::floor(ty);
  f.base = {static_cast<int>(bx), static_cast<int>(by)};
  f.frac = {static_cast<float>(tx - bx), static_cast<float>(ty - by)};
  f.per_unit = glm::vec2(static_cast<float>(1 / size));
  return f;
}

size_t ImageLayers::upload_loaded() {
  size_t n = 0;
  for (size_t i = 0; i < layers_.size(); ++i)
    for (auto& [slot, mips] : layers_[i].cache->take_loaded()) {
      renderer_.upload(i, slot, mips);
      ++n;
    }
  return n;
}

double ImageLayers::draw(const LayerPass& pass) {
  const GBuffer& g = pass.g;
  const View& view = pass.view;
  const WorldFrame& world = pass.world;
  const Loading loading = pass.loading;
  const ShadingSettings& sh = pass.shading;
  const bool lens = sh.lens_shows == ShadingSettings::LensShows::kImages;
  renderer_.set_lens_only(float(sh.lens_x), float(sh.lens_y), float(lens ? sh.lens_radius : 0.0));
  const ImageLighting lighting =
      pass.imagery_unlit ? ImageLighting::kUnlit : ImageLighting::kHillshade;
  const double sun_z = std::sin(sh.sun_altitude_deg * std::numbers::pi / 180);
  const float light_norm = static_cast<float>(0.12 + 0.88 * std::max(sun_z, 0.05));
  std::vector<const ImageCache*> caches;
  std::vector<ImageLayerFrame> frames;
  for (const Layer& l : layers_) {
    caches.push_back(l.cache.get());
    frames.push_back(frame_of(l, view, world));
  }
  double ms = 0;
  int idle_rounds = 0;
  for (int round = 0;; ++round) {
    passes_ = round + 1;
    for (Layer& l : layers_)
      l.cache->begin_frame();
    const size_t loaded = upload_loaded();
    ImageFeedback fb;
    ms = renderer_.draw(g, view, world, caches, frames, lighting, light_norm, ++frame_, fb);
    bool wanted = false, busy = false;
    for (size_t i = 0; i < layers_.size(); ++i) {
      ImageCache& c = *layers_[i].cache;
      for (uint32_t s : fb.used[i])
        c.mark_used(s);
      for (const tileformat::TileId& id : fb.requests[i])
        wanted = c.request(id) || wanted;
      c.flush_requests();
      busy = busy || c.loader_busy();
    }
    if (loading == Loading::kAsReady || (!wanted && !busy)) break;
    // Tiles that cannot get a slot are asked for again and again.
    idle_rounds = loaded == 0 && !busy ? idle_rounds + 1 : 0;
    if (idle_rounds > 3 || round > 200) break;
    for (Layer& l : layers_)
      if (l.cache->loader_busy()) l.cache->wait_for_loader();
  }
  return ms;
}

bool ImageLayers::loading() {
  for (Layer& l : layers_)
    if (l.cache->loader_busy()) return true;
  return false;
}

size_t ImageLayers::waiting() const {
  size_t n = 0;
  for (const ImageCacheStats& st : stats())
    n += st.loading;
  return n;
}

std::string ImageLayers::stats_json(double ms) const {
  ImageCacheStats sum;
  for (const ImageCacheStats& s : stats()) {
    sum.slots += s.slots, sum.resident += s.resident, sum.known_absent += s.known_absent;
    sum.loaded += s.loaded, sum.broken += s.broken, sum.bytes_read += s.bytes_read;
    sum.evictions += s.evictions;
  }
  char text[640];
  std::snprintf(
      text, sizeof text,
      ", \"image_layers\": %zu, \"images_ms\": %.3f, \"image_passes\": %d, "
      "\"image_tiles_resident\": %zu, \"image_tiles_absent\": %zu, "
      "\"image_tiles_loaded\": %llu, \"image_evictions\": %llu, "
      "\"broken_image_tiles\": %llu, \"image_bytes_read\": %llu",
      size(), ms, passes(), sum.resident, sum.known_absent,
      static_cast<unsigned long long>(sum.loaded), static_cast<unsigned long long>(sum.evictions),
      static_cast<unsigned long long>(sum.broken), static_cast<unsigned long long>(sum.bytes_read));
  return text;
}

std::vector<ImageCacheStats> ImageLayers::stats() const {
  std::vector<ImageCacheStats> s;
  for (const Layer& l : layers_)
    s.push_back(l.cache->stats());
  return s;
}

}  // namespace globe::viewer
