// Headless session (see headless_run.hpp).
#include "app/headless_run.hpp"

#include "data/network.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "app/image_file.hpp"
#include "app/mesh_file.hpp"
#include "app/terrain_scene.hpp"
#include "app/text_file.hpp"
#include "platform/gl.hpp"
#include "platform/headless_context.hpp"
#include "runtime/errors.hpp"

namespace globe::viewer {

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : (v[v.size() / 2 - 1] + v[v.size() / 2]) / 2;
}

// The pixel (from the top-left) where the point lon/lat (degrees) at height 0
// lands in `view`; {-1, -1} when it is behind the eye or not in the tiling.
std::pair<int, int> pixel_of(const View& view, const WorldFrame& world, double lon, double lat) {
  glm::dvec2 crs;
  try {
    crs = world.lonlat_to_crs(lon, lat);
  } catch (const std::exception&) {
    return {-1, -1};
  }
  const glm::dvec2 key = world.crs_to_key(crs.x, crs.y);
  const glm::dvec3 p = world.key_to_world(key.x, key.y, 0, view.origin);
  const glm::dvec4 clip = view.proj * view.view * glm::dvec4(p, 1);
  if (clip.w <= 0) return {-1, -1};
  const double x = (clip.x / clip.w + 1) / 2 * view.width,
               y = (1 - clip.y / clip.w) / 2 * view.height;
  return {static_cast<int>(std::floor(x)), static_cast<int>(std::floor(y))};
}

// --pick: what lies at each pixel (or where each lon/lat lands) in frame
// `f`, one line each on stdout; a picked line is highlighted by drawing the
// last pose (`last`) again into `f`.
// --pick-format json: one object per pick (docs/viewer.md "Picking").
void run_json_picks(const ViewerSettings& settings, TerrainScene& scene, const FrameResult& f) {
  for (const ViewerSettings::PickAt& at : settings.picks) {
    const auto [x, y] = at.geographic ? pixel_of(f.view, scene.world(), at.a, at.b)
                                      : std::pair(int(at.a), int(at.b));
    std::string out = "{\"x\": " + std::to_string(x) + ", \"y\": " + std::to_string(y);
    if (const auto g = scene.ground_at(f.view, x, y)) {
      char buf[128];
      std::snprintf(buf, sizeof buf, ", \"lon\": %.9f, \"lat\": %.9f, \"height\": %.3f", g->x, g->y,
                    g->z);
      out += buf;
    } else {
      out += ", \"lon\": null, \"lat\": null, \"height\": null";
    }
    // The topmost feature of each kind: the last layer of that kind.
    for (const char* kind : {"area", "line", "chart"}) {
      std::string value = "null";
      for (const auto& layer : scene.layers())
        if (std::string(layer->pick_kind()) == kind) value = layer->pick_json(x, y);
      out += ", \"" + std::string(kind) + "\": " + value;
    }
    std::printf("%s}\n", out.c_str());
  }
}

void run_picks(const ViewerSettings& settings, TerrainScene& scene, const CameraPose& last,
               FrameResult& f) {
  if (settings.pick_json) return run_json_picks(settings, scene, f);
  SceneLayer* layer = scene.picking_layer();  // the topmost: charts over lines over areas
  if (!layer)
    throw UsageError("--pick finds charts, lines or areas; give a point, line or area package too");
  // Every pick reads the frame drawn; the last one's highlight shows in the next.
  for (size_t i = 0; i < settings.picks.size(); ++i) {
    const ViewerSettings::PickAt& at = settings.picks[i];
    const auto [x, y] = at.geographic ? pixel_of(f.view, scene.world(), at.a, at.b)
                                      : std::pair(int(at.a), int(at.b));
    std::printf("%s\n", layer->pick(x, y, i + 1 == settings.picks.size()).c_str());
  }
  // A highlighted pick shows in the snapshot: one more frame.
  if (layer->picked_highlight())
    f = scene.frame(last, Loading::kSettle, TerrainScene::Output::kDraw);
}

}  // namespace

int run_headless(const ViewerSettings& settings) {
  const auto t_start = std::chrono::steady_clock::now();
  std::unique_ptr<HeadlessContext> context;
  try {
    context = create_headless_context(settings.platform == "auto" ? "auto" : settings.platform);
  } catch (const std::exception& e) {
    throw OutputError(std::string("cannot render headless: ") + e.what());
  }
  TerrainScene scene(settings);
  const CameraPose start = scene.initial_pose();
  std::vector<CameraPose> poses = settings.camera_path;
  if (poses.empty()) poses.push_back(start);

  // Time to first frame: opening, the first complete selection, one draw.
  FrameResult f = scene.frame(poses.front(), Loading::kSettle, TerrainScene::Output::kDraw);
  gl::Finish();
  const double first_frame_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t_start).count();

  // Whether any pose's frame showed terrain (read outside the timed frames).
  double ground = 0, most_ground = 0;
  std::vector<double> frame_ms, terrain_ms, select_ms;
  std::vector<std::vector<double>> layer_ms(scene.layers().size());
  uint64_t max_resident = scene.cache().stats().resident_bytes;
  std::string labels_json;  // --labels-json: one object per frame
  int frame_no = 0;
  for (size_t i = 0; i < poses.size(); ++i) {
    const int frames = settings.stats ? settings.frames : 1;
    for (int k = 0; k < frames; ++k) {
      const auto t0 = std::chrono::steady_clock::now();
      f = scene.frame(poses[i], Loading::kSettle, TerrainScene::Output::kDraw);
      gl::Finish();
      if (settings.labels_json) {
        const CameraPose& p = poses[i];
        const std::string frame =
            scene.labels() ? scene.labels()->frame_json()
                           : std::string("{\"candidates\": 0, \"shown\": 0, \"labels\": []}");
        char pose[160];
        std::snprintf(pose, sizeof pose, "[%.9g, %.9g, %.9g, %.9g, %.9g]", p.lon, p.lat, p.height_m,
                      p.heading_deg, p.pitch_deg);
        labels_json += std::string(labels_json.empty() ? "" : ",\n") +
                       "{\"frame\": " + std::to_string(frame_no) + ", \"pose\": " + pose + ", " +
                       frame.substr(1);
      }
      ++frame_no;
      frame_ms.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      terrain_ms.push_back(f.terrain_ms);
      for (size_t l = 0; l < f.layer_ms.size(); ++l)
        layer_ms[l].push_back(f.layer_ms[l]);
      select_ms.push_back(f.select_ms);
      max_resident = std::max(max_resident, scene.cache().stats().resident_bytes);
    }
    ground = scene.ground_fraction();
    most_ground = std::max(most_ground, ground);
  }
  if (!settings.picks.empty()) run_picks(settings, scene, poses.back(), f);
  if (settings.labels_json)
    write_text_file(*settings.labels_json, "{\"width\": " + std::to_string(settings.width) +
                                               ", \"height\": " + std::to_string(settings.height) +
                                               ", \"frames\": [\n" + labels_json + "\n]}\n");
  if (settings.snapshot)
    write_png(*settings.snapshot, scene.read_pixels(), scene.renderer().width(),
              scene.renderer().height());
  if (settings.export_mesh)
    write_mesh_ply(*settings.export_mesh, scene.capture(f), f.view, scene.world(),
                   settings.shading.exaggeration, settings.max_error_px);
  if (settings.stats) {
    const CacheStats cs = scene.cache().stats();
    const size_t triangles = f.patches.size() * scene.renderer().triangles_per_patch();
    // Triangles of the full-resolution grid over the same area: two per
    // finest-zoom cell (a patch's legs span L lattice steps of |u| samples).
    double full_res = 0;
    const double L = scene.package().lattice;
    for (const Patch& p : f.patches) {
      const double scale = std::ldexp(1.0, 2 * (scene.package().max_zoom - p.tile.z));
      full_res += L * L * double(p.u.x * p.u.x + p.u.y * p.u.y) * scale;
    }
    std::printf(
        "{\"platform\": \"%s\", \"surface\": \"%s\", \"width\": %d, \"height\": %d, "
        "\"frames\": %zu, "
        "\"frame_ms\": %.3f, \"terrain_ms\": %.3f, \"select_ms\": %.3f, "
        "\"first_frame_ms\": %.1f, \"patches\": %zu, \"triangles\": %zu, "
        "\"full_res_triangles\": %.0f, "
        "\"max_error_px\": %g, \"vertices_evaluated\": %zu, \"waiting\": %zu, "
        "\"resident_blocks\": %zu, \"resident_bytes\": %llu, \"max_resident_bytes\": %llu, "
        "\"budget_bytes\": %llu, \"blocks_loaded\": %llu, \"evictions\": %llu, "
        "\"broken_tiles\": %llu, \"bytes_read\": %llu, \"camera\": \"%s\"",
        context->platform().c_str(), scene.world().globe() ? "globe" : "flat",
        scene.renderer().width(), scene.renderer().height(), frame_ms.size(), median(frame_ms),
        median(terrain_ms), median(select_ms), first_frame_ms, f.patches.size(), triangles,
        full_res, settings.max_error_px, f.selection.vertices_evaluated, f.selection.waiting,
        cs.resident, static_cast<unsigned long long>(cs.resident_bytes),
        static_cast<unsigned long long>(max_resident),
        static_cast<unsigned long long>(cs.budget_bytes),
        static_cast<unsigned long long>(cs.blocks_loaded),
        static_cast<unsigned long long>(cs.evictions), static_cast<unsigned long long>(cs.broken),
        static_cast<unsigned long long>(cs.bytes_read), f.pose.str().c_str());
    std::printf(", \"ground_fraction\": %.4f", ground);
    const auto [ramp_lo, ramp_hi] = scene.ramp().data_range();
    std::printf(", \"height_range\": [%.2f, %.2f]", ramp_lo, ramp_hi);
    const DataRanges& dr = scene.data_ranges();
    std::printf(", \"slope_ramp_top_deg\": %.2f, \"skyview_ramp_low\": %.4f", dr.slope_top_deg,
                dr.sky_low);
    for (size_t l = 0; l < scene.layers().size(); ++l)
      std::printf("%s", scene.layers()[l]->stats_json(median(layer_ms[l])).c_str());
    if (Network* net = Network::current())
      if (const auto n = net->stats())
        std::printf(
            ", \"network\": {\"requests\": %llu, \"bytes\": %llu, \"cache_hits\": %llu, "
            "\"revalidated\": %llu, \"retries\": %llu, \"no_content\": %llu, \"broken\": %llu, "
            "\"failed\": %llu}",
            static_cast<unsigned long long>(n->requests), static_cast<unsigned long long>(n->bytes),
            static_cast<unsigned long long>(n->cache_hits),
            static_cast<unsigned long long>(n->revalidated),
            static_cast<unsigned long long>(n->retries),
            static_cast<unsigned long long>(n->no_content),
            static_cast<unsigned long long>(n->broken), static_cast<unsigned long long>(n->failed));
    std::printf("}\n");
  }
  if (most_ground == 0 && scene.cache().stats().broken > 0) {
    std::fprintf(stderr,
                 "globe-view: the frame shows no terrain: its tiles could not be read (see the "
                 "warnings above)%s\n",
                 settings.snapshot ? "; the image was written" : "");
    return kExitBlankFrame;
  }
  if (most_ground == 0) {
    std::fprintf(stderr,
                 "globe-view: the frame%s no terrain: the camera (%s) looks away from the data "
                 "or off it; try --fit, or a --camera over the package's bounds%s\n",
                 poses.size() > 1 ? "s of the camera path show" : " shows", f.pose.str().c_str(),
                 settings.snapshot ? " (the image was written)" : "");
    return kExitBlankFrame;
  }
  return kExitOk;
}

}  // namespace globe::viewer
