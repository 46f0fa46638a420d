// Interactive session (see window_run.hpp).
//   left drag: orbit   right drag / arrows: pan   wheel / W,S: zoom
//   1-7: the shading modes (render/shading_modes.cpp)   +/-: exaggeration
//   , . shift the elevation ramp, ; ' narrow / widen it, 0 resets it
//   R: reset view   P: screenshot (globe-view-N.png)   Esc: quit
#define GLFW_INCLUDE_NONE
#include "app/window_run.hpp"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numbers>

#include "app/image_file.hpp"
#include "app/terrain_scene.hpp"
#include "camera/orbit.hpp"
#include "platform/glfw_window.hpp"
#include "render/readback.hpp"
#include "runtime/errors.hpp"

namespace globe::viewer {

namespace {

constexpr double kDeg = std::numbers::pi / 180;

}  // namespace

int run_window(const ViewerSettings& settings) {
  bool drag_orbit = false, drag_pan = false;
  double last_x = 0, last_y = 0;
  Orbit orbit, home;
  TerrainScene* scene = nullptr;
  int screenshot = 0;
  size_t layer = 0;  // the image layer that V, [ and ] act on
  View last_view;    // the last frame's view: G-buffer points are relative to its origin
  bool have_view = false;
  bool screenshot_pending = false;
  GlfwWindow* window_ptr = nullptr;

  WindowCallbacks cb;
  double press_x = 0, press_y = 0;
  std::string picked;  // the line the last click picked
  cb.on_button = [&](int button, bool down, double x, double y) {
    if (button == GLFW_MOUSE_BUTTON_LEFT) {
      drag_orbit = down;
      // A click, not a drag: pick the line under it (or clear).
      if (down)
        press_x = x, press_y = y;
      else if (scene && scene->lines() && std::hypot(x - press_x, y - press_y) < 4)
        picked = scene->lines()->pick(int(x), int(y));
    }
    if (button == GLFW_MOUSE_BUTTON_RIGHT) drag_pan = down;
    last_x = x, last_y = y;
  };
  cb.on_cursor = [&](double x, double y) {
    const double dx = x - last_x, dy = y - last_y;
    last_x = x, last_y = y;
    if (drag_orbit) {
      orbit.turn(-dx * 0.3, dy * 0.3);
    } else if (drag_pan && scene) {
      orbit.pan(dx, dy, scene->renderer().height() / (2 * std::tan(settings.fov_y_deg * kDeg / 2)),
                scene->world());
    }
  };
  // The wheel zooms towards the terrain point under the cursor.
  cb.on_scroll = [&](double dy) {
    if (!scene) return;
    const glm::vec4 p = read_position(scene->renderer().gbuffer().fbo, int(last_x), int(last_y),
                                      scene->renderer().height());
    const glm::dvec3 under(p.x, p.y, p.z);
    orbit.zoom(std::pow(0.85, dy), scene->world(), &last_view,
               p.w > 0.5 && have_view ? &under : nullptr);
  };
  cb.on_key = [&](int key, int) {
    if (!scene) return;
    ShadingSettings& s = scene->settings().shading;
    const double px = scene->renderer().height() / (2 * std::tan(settings.fov_y_deg * kDeg / 2));
    switch (key) {
      case GLFW_KEY_ESCAPE:
        window_ptr->close();
        break;
      case GLFW_KEY_R:
        orbit = home;
        break;
      case GLFW_KEY_P:
        screenshot_pending = true;
        break;
      case GLFW_KEY_O: {  // only with the analysis layers it draws
        ShadingSettings next = s;
        next.ambient_occlusion = !s.ambient_occlusion;
        if (const std::string e = scene->shading_problem(next); !e.empty())
          std::fprintf(stderr, "globe-view: %s\n", e.c_str());
        else
          s = next;
        break;
      }
      case GLFW_KEY_PAGE_UP:
      case GLFW_KEY_PAGE_DOWN: {  // lifted lines: from the automatic lift on
        auto& settings = scene->settings();
        const double lift = settings.lift_m ? *settings.lift_m : 0.03 * glm::length(last_view.eye);
        settings.lift_m = std::max(1.0, lift * (key == GLFW_KEY_PAGE_UP ? 1.5 : 1 / 1.5));
        std::fprintf(stderr, "globe-view: lines lifted %.0f m\n", *settings.lift_m);
        break;
      }
      case GLFW_KEY_C:
        if (scene->charts()) scene->charts()->next_kind();
        break;
      case GLFW_KEY_F5:
        if (scene->charts()) scene->charts()->reload_style(ChartLayer::Reload::kAlways);
        if (scene->lines()) scene->lines()->reload_style(LineLayer::Reload::kAlways);
        if (scene->ramp().reload(ElevationRamp::Reload::kAlways)) scene->apply_ramp();
        break;
      case GLFW_KEY_COMMA:  // the elevation ramp: shift down / up, narrow / widen, reset
        scene->ramp().shift(-0.05);
        scene->apply_ramp();
        break;
      case GLFW_KEY_PERIOD:
        scene->ramp().shift(0.05);
        scene->apply_ramp();
        break;
      case GLFW_KEY_SEMICOLON:
        scene->ramp().stretch(1 / 1.1);
        scene->apply_ramp();
        break;
      case GLFW_KEY_APOSTROPHE:
        scene->ramp().stretch(1.1);
        scene->apply_ramp();
        break;
      case GLFW_KEY_0:
        scene->ramp().reset();
        scene->apply_ramp();
        break;
      case GLFW_KEY_L:
        // deferred -> geometry (flat frame only) -> lifted -> deferred
        if (LineLayer* l = scene->lines())
          l->set_mode(l->mode() == LineMode::kDeferred && !scene->world().globe()
                          ? LineMode::kGeometry
                      : l->mode() == LineMode::kLifted ? LineMode::kDeferred
                                                       : LineMode::kLifted);
        break;
      case GLFW_KEY_I:
        if (ImageLayers* im = scene->images()) layer = (layer + 1) % im->size();
        break;
      case GLFW_KEY_V:
        if (ImageLayers* im = scene->images()) im->set_visible(layer, !im->visible(layer));
        break;
      case GLFW_KEY_LEFT_BRACKET:
        if (ImageLayers* im = scene->images()) im->set_opacity(layer, im->opacity(layer) - 0.1);
        break;
      case GLFW_KEY_RIGHT_BRACKET:
        if (ImageLayers* im = scene->images()) im->set_opacity(layer, im->opacity(layer) + 0.1);
        break;
      case GLFW_KEY_U:
        if (scene->images()) scene->settings().imagery_unlit = !scene->settings().imagery_unlit;
        break;
      case GLFW_KEY_EQUAL:
      case GLFW_KEY_KP_ADD:
        s.exaggeration = std::min(s.exaggeration * 1.25, 100.0);
        break;
      case GLFW_KEY_MINUS:
      case GLFW_KEY_KP_SUBTRACT:
        s.exaggeration = std::max(s.exaggeration / 1.25, 0.1);
        break;
      case GLFW_KEY_W:
        orbit.zoom(0.85, scene->world());
        break;
      case GLFW_KEY_S:
        orbit.zoom(1 / 0.85, scene->world());
        break;
      case GLFW_KEY_LEFT:
        orbit.pan(-40, 0, px, scene->world());
        break;
      case GLFW_KEY_RIGHT:
        orbit.pan(40, 0, px, scene->world());
        break;
      case GLFW_KEY_UP:
        orbit.pan(0, -40, px, scene->world());
        break;
      case GLFW_KEY_DOWN:
        orbit.pan(0, 40, px, scene->world());
        break;
      default:
        if (const ShadingMode* m = shading_mode_for_key(key)) {  // a mode's key
          ShadingSettings next = s;
          next.mode = m->id;
          if (const std::string e = scene->shading_problem(next); !e.empty())
            std::fprintf(stderr, "globe-view: %s\n", e.c_str());
          else
            s = next;
        }
        break;
    }
  };

  // No display at all is a usage error (exit 2): the user asked for a window
  // where none can open.
  if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY"))
    throw UsageError(
        "no display to open a window on (DISPLAY is not set): pass --snapshot OUT.png to render "
        "headless, or run under a display (e.g. xvfb-run)");
  std::unique_ptr<GlfwWindow> window;
  try {
    window = std::make_unique<GlfwWindow>(settings.width, settings.height, "globe-view", cb);
  } catch (const std::exception& e) {
    throw OutputError(std::string(e.what()) + "; pass --snapshot OUT.png to render headless");
  }
  window_ptr = window.get();
  TerrainScene s(settings);
  scene = &s;
  const CameraPose start = s.initial_pose();
  const auto [data_lo, data_hi] = s.ramp().data_range();
  const double ground = (data_lo + data_hi) / 2;
  home = orbit = Orbit::from_pose(start, s.world(), ground);

  auto last_title = std::chrono::steady_clock::now();
  const auto opened = last_title;
  // Drawn on demand: while anything moves, loads or animates, every frame;
  // after that a few more (uploads, the title), then the window sleeps until
  // an event (or every 0.5 s, to notice edited style and colour files).
  constexpr int kSettleFrames = 3;
  int frames_due = kSettleFrames;
  uint64_t events_seen = window->events();
  while (!window->should_close()) {
    if (frames_due > 0 || settings.flow_animate)
      window->poll();
    else
      window->wait(0.5);
    if (window->events() != events_seen) {
      events_seen = window->events();
      frames_due = kSettleFrames;
    }
    const auto now = std::chrono::steady_clock::now();
    if (now - last_title > std::chrono::milliseconds(500)) {
      // Edits of the style and colour files are picked up.
      bool edited = s.lines() && s.lines()->reload_style(LineLayer::Reload::kIfChanged);
      edited = (s.charts() && s.charts()->reload_style(ChartLayer::Reload::kIfChanged)) || edited;
      if (s.ramp().reload(ElevationRamp::Reload::kIfChanged)) {
        s.apply_ramp();
        edited = true;
      }
      if (edited) frames_due = kSettleFrames;
      if (frames_due == 0 && !settings.flow_animate) last_title = now;
    }
    if (frames_due == 0 && !settings.flow_animate) continue;
    if (settings.flow_animate)  // a cycle of the flow pulses every 2 s
      s.settings().shading.flow_phase = std::fmod(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - opened).count() / 2,
          1.0);
    int w = 0, h = 0;
    window->framebuffer_size(w, h);
    if (w <= 0 || h <= 0) continue;
    s.resize(w, h);
    const auto t0 = std::chrono::steady_clock::now();
    const FrameResult f = s.frame(orbit.pose(s.world(), settings.fov_y_deg), Loading::kAsReady,
                                  TerrainScene::Output::kDraw);
    last_view = f.view;
    have_view = true;
    size_t waiting = f.selection.waiting;  // blocks and image tiles not in yet
    if (const ImageLayers* im = s.images())
      for (const ImageCacheStats& st : im->stats())
        waiting += st.loading;
    frames_due = waiting > 0 || s.loading() ? kSettleFrames : std::max(0, frames_due - 1);
    if (screenshot_pending) {
      const std::string name = "globe-view-" + std::to_string(++screenshot) + ".png";
      write_png(name, s.read_pixels(), w, h);
      std::fprintf(stderr, "globe-view: wrote %s\n", name.c_str());
      screenshot_pending = false;
    }
    blit_to_window(s.output_fbo(), s.renderer().width(), s.renderer().height(), w, h);
    window->swap();
    // The title every 0.5 s, and on the last frame before the window sleeps.
    const auto drawn = std::chrono::steady_clock::now();
    if (drawn - last_title > std::chrono::milliseconds(500) || frames_due == 0) {
      const double ms = std::chrono::duration<double, std::milli>(drawn - t0).count();
      char title[320];
      std::snprintf(title, sizeof title,
                    "globe-view  %.1f ms (lines %.1f)  %zu patches  %zu k triangles  %zu blocks  "
                    "waiting %zu",
                    ms, f.lines_ms, f.patches.size(),
                    f.patches.size() * s.renderer().triangles_per_patch() / 1000,
                    s.cache().stats().resident, waiting);
      if (const ImageLayers* im = s.images()) {
        const size_t n = std::strlen(title);
        std::snprintf(title + n, sizeof title - n, "  image %zu/%zu %s %.1f", layer + 1, im->size(),
                      im->visible(layer) ? "opacity" : "hidden, opacity", im->opacity(layer));
      }
      if (!picked.empty()) {
        const std::string rest = title;
        std::snprintf(title, sizeof title, "globe-view  %s  %s", picked.c_str(),
                      rest.c_str() + std::strlen("globe-view  "));
      }
      // The place whose chart is under the cursor.
      if (ChartLayer* charts = s.charts()) {
        const std::string place = charts->describe(int(last_x), int(last_y));
        if (!place.empty())
          std::snprintf(title, sizeof title, "globe-view  %s  waiting %zu", place.c_str(), waiting);
      }
      window->set_title(title);
      last_title = drawn;
    }
  }
  return kExitOk;
}

}  // namespace globe::viewer
