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
#include <numeric>

#include "app/image_file.hpp"
#include "app/terrain_scene.hpp"
#include "camera/orbit.hpp"
#include "platform/glfw_window.hpp"
#include "render/readback.hpp"
#include "runtime/errors.hpp"

namespace globe::viewer {

namespace {

constexpr double kDeg = std::numbers::pi / 180;
// Drawn on demand: while anything moves, loads or animates, every frame;
// after that this many more (uploads, the title), then the window sleeps
// until an event (or every 0.5 s, to notice edited style and colour files).
constexpr int kSettleFrames = 3;
constexpr auto kTitleEvery = std::chrono::milliseconds(500);

// One interactive session: the window, the scene, the orbit camera and what
// the mouse and keys change.
class WindowSession {
 public:
  explicit WindowSession(const ViewerSettings& settings) : settings_(settings) {}
  int run();

 private:
  WindowCallbacks callbacks();
  void on_button(int button, bool down, double x, double y);
  void on_cursor(double x, double y);
  void on_scroll(double dy, int mods);
  void on_key(int key);
  // The key groups of on_key; each returns whether it knew the key.
  bool camera_key(int key);
  bool ramp_key(int key);
  bool layer_key(int key);
  void shading_key(int key);
  void try_shading(const ShadingSettings& next);  // applies it unless a layer it needs is missing
  double pixels_per_radian() const {
    return scene_->renderer().height() / (2 * std::tan(settings_.fov_y_deg * kDeg / 2));
  }
  bool reload_edited_files();  // true when a style or colour file changed
  void draw(int width, int height);
  void set_title(const FrameResult& f, double ms, size_t waiting);

  const ViewerSettings& settings_;
  std::unique_ptr<GlfwWindow> window_;
  std::unique_ptr<TerrainScene> scene_;
  Orbit orbit_, home_;
  bool drag_orbit_ = false, drag_pan_ = false;
  double last_x_ = 0, last_y_ = 0, press_x_ = 0, press_y_ = 0;
  int screenshot_ = 0;
  bool screenshot_pending_ = false;
  size_t layer_ = 0;  // the image layer that V, [ and ] act on
  View last_view_;    // the last frame's view: G-buffer points are relative to its origin
  bool have_view_ = false;
  std::string picked_;         // the line the last click picked
  bool lens_follows_ = false;  // K: the lens is on and follows the pointer
  int frames_due_ = kSettleFrames;
  std::chrono::steady_clock::time_point opened_ = std::chrono::steady_clock::now(),
                                        last_title_ = opened_;
};

WindowCallbacks WindowSession::callbacks() {
  WindowCallbacks cb;
  cb.on_button = [this](int button, bool down, double x, double y) {
    on_button(button, down, x, y);
  };
  cb.on_cursor = [this](double x, double y) { on_cursor(x, y); };
  cb.on_scroll = [this](double dy, int mods) { on_scroll(dy, mods); };
  cb.on_key = [this](int key, int) { on_key(key); };
  return cb;
}

void WindowSession::on_button(int button, bool down, double x, double y) {
  if (button == GLFW_MOUSE_BUTTON_LEFT) {
    drag_orbit_ = down;
    // A click, not a drag: pick the line under it (or clear).
    if (down)
      press_x_ = x, press_y_ = y;
    else if (scene_ && scene_->lines() && std::hypot(x - press_x_, y - press_y_) < 4)
      picked_ = scene_->lines()->pick(int(x), int(y), true);
  }
  if (button == GLFW_MOUSE_BUTTON_RIGHT) drag_pan_ = down;
  last_x_ = x, last_y_ = y;
}

void WindowSession::on_cursor(double x, double y) {
  const double dx = x - last_x_, dy = y - last_y_;
  last_x_ = x, last_y_ = y;
  if (lens_follows_ && scene_) {  // the lens moves with the pointer
    scene_->settings().shading.lens_x = x;
    scene_->settings().shading.lens_y = y;
  }
  if (drag_orbit_)
    orbit_.turn(-dx * 0.3, dy * 0.3);
  else if (drag_pan_ && scene_)
    orbit_.pan(dx, dy, pixels_per_radian(), scene_->world());
}

// The wheel zooms towards the terrain point under the cursor; with Shift
// held while the lens follows the pointer, it resizes the lens.
void WindowSession::on_scroll(double dy, int mods) {
  if (!scene_) return;
  if (lens_follows_ && (mods & GLFW_MOD_SHIFT)) {
    double& r = scene_->settings().shading.lens_radius;
    r = std::clamp(r * std::pow(1.15, dy), 8.0, 4000.0);
    return;
  }
  const glm::vec4 p = read_position(scene_->renderer().gbuffer().fbo, int(last_x_), int(last_y_),
                                    scene_->renderer().height());
  const glm::dvec3 under(p.x, p.y, p.z);
  orbit_.zoom(std::pow(0.85, dy), scene_->world(), &last_view_,
              p.w > 0.5 && have_view_ ? &under : nullptr);
}

void WindowSession::on_key(int key) {
  if (!scene_) return;
  if (camera_key(key) || ramp_key(key) || layer_key(key)) return;
  shading_key(key);
}

// Escape, R, P, W/S, the arrows.
bool WindowSession::camera_key(int key) {
  switch (key) {
    case GLFW_KEY_ESCAPE:
      window_->close();
      return true;
    case GLFW_KEY_R:
      orbit_ = home_;
      return true;
    case GLFW_KEY_P:
      screenshot_pending_ = true;
      return true;
    case GLFW_KEY_W:
      orbit_.zoom(0.85, scene_->world());
      return true;
    case GLFW_KEY_S:
      orbit_.zoom(1 / 0.85, scene_->world());
      return true;
    case GLFW_KEY_LEFT:
    case GLFW_KEY_RIGHT:
      orbit_.pan(key == GLFW_KEY_LEFT ? -40 : 40, 0, pixels_per_radian(), scene_->world());
      return true;
    case GLFW_KEY_UP:
    case GLFW_KEY_DOWN:
      orbit_.pan(0, key == GLFW_KEY_UP ? -40 : 40, pixels_per_radian(), scene_->world());
      return true;
    default:
      return false;
  }
}

// The elevation ramp: , . shift it down / up, ; ' narrow / widen it, 0 resets
// it; F5 reloads the style and colour files.
bool WindowSession::ramp_key(int key) {
  ElevationRamp& ramp = scene_->ramp();
  switch (key) {
    case GLFW_KEY_COMMA:
      ramp.shift(-0.05);
      break;
    case GLFW_KEY_PERIOD:
      ramp.shift(0.05);
      break;
    case GLFW_KEY_SEMICOLON:
      ramp.stretch(1 / 1.1);
      break;
    case GLFW_KEY_APOSTROPHE:
      ramp.stretch(1.1);
      break;
    case GLFW_KEY_0:
      ramp.reset();
      break;
    case GLFW_KEY_F5:
      for (const auto& layer : scene_->layers())
        layer->reload_style(true);
      if (!ramp.reload(ElevationRamp::Reload::kAlways)) return true;
      break;
    default:
      return false;
  }
  scene_->apply_ramp();
  return true;
}

// Image layers (I, V, [ ], U), lines (L, PageUp/PageDown), charts (C).
bool WindowSession::layer_key(int key) {
  ImageLayers* im = scene_->images();
  switch (key) {
    case GLFW_KEY_I:
      if (im) layer_ = (layer_ + 1) % im->size();
      return true;
    case GLFW_KEY_V:
      if (im) im->set_visible(layer_, !im->visible(layer_));
      return true;
    case GLFW_KEY_LEFT_BRACKET:
    case GLFW_KEY_RIGHT_BRACKET:
      if (im)
        im->set_opacity(layer_, im->opacity(layer_) + (key == GLFW_KEY_LEFT_BRACKET ? -0.1 : 0.1));
      return true;
    case GLFW_KEY_U:
      if (im) scene_->settings().imagery_unlit = !scene_->settings().imagery_unlit;
      return true;
    case GLFW_KEY_L:
      // deferred -> geometry (flat frame only) -> lifted -> deferred
      if (LineLayer* l = scene_->lines())
        l->set_mode(l->mode() == LineMode::kDeferred && !scene_->world().globe()
                        ? LineMode::kGeometry
                    : l->mode() == LineMode::kLifted ? LineMode::kDeferred
                                                     : LineMode::kLifted);
      return true;
    case GLFW_KEY_PAGE_UP:
    case GLFW_KEY_PAGE_DOWN: {  // lifted lines: from the automatic lift on
      ViewerSettings& v = scene_->settings();
      const double lift = v.lift_m ? *v.lift_m : 0.03 * glm::length(last_view_.eye);
      v.lift_m = std::max(1.0, lift * (key == GLFW_KEY_PAGE_UP ? 1.5 : 1 / 1.5));
      std::fprintf(stderr, "globe-view: lines lifted %.0f m\n", *v.lift_m);
      return true;
    }
    case GLFW_KEY_C:
      if (scene_->charts()) scene_->charts()->next_kind();
      return true;
    case GLFW_KEY_N:  // names on/off
      if (scene_->labels()) scene_->labels()->toggle();
      return true;
    default:
      return false;
  }
}

// A shading mode's key (render/shading_modes.cpp), O ambient occlusion, K the
// lens, +/- exaggeration.
void WindowSession::shading_key(int key) {
  ShadingSettings next = scene_->settings().shading;
  if (key == GLFW_KEY_O) {
    next.ambient_occlusion = !next.ambient_occlusion;
  } else if (key == GLFW_KEY_K) {  // the lens on (following the pointer) / off
    lens_follows_ = !lens_follows_;
    next.lens_radius =
        lens_follows_ ? (settings_.shading.lens_radius > 0 ? settings_.shading.lens_radius : 120)
                      : 0;
    next.lens_x = last_x_, next.lens_y = last_y_;
  } else if (key == GLFW_KEY_EQUAL || key == GLFW_KEY_KP_ADD) {
    next.exaggeration = std::min(next.exaggeration * 1.25, 100.0);
  } else if (key == GLFW_KEY_MINUS || key == GLFW_KEY_KP_SUBTRACT) {
    next.exaggeration = std::max(next.exaggeration / 1.25, 0.1);
  } else if (const ShadingMode* m = shading_mode_for_key(key)) {
    next.mode = m->id;
  } else {
    return;
  }
  try_shading(next);
}

void WindowSession::try_shading(const ShadingSettings& next) {
  if (const std::string e = scene_->shading_problem(next); !e.empty())
    std::fprintf(stderr, "globe-view: %s\n", e.c_str());
  else
    scene_->settings().shading = next;
}

bool WindowSession::reload_edited_files() {
  TerrainScene& s = *scene_;
  bool edited = false;
  for (const auto& layer : s.layers())
    edited = layer->reload_style(false) || edited;
  if (s.ramp().reload(ElevationRamp::Reload::kIfChanged)) {
    s.apply_ramp();
    edited = true;
  }
  return edited;
}

int WindowSession::run() {
  // No display at all is a usage error (exit 2): the user asked for a window
  // where none can open.
  if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY"))
    throw UsageError(
        "no display to open a window on (DISPLAY is not set): pass --snapshot OUT.png to render "
        "headless, or run under a display (e.g. xvfb-run)");
  try {
    window_ =
        std::make_unique<GlfwWindow>(settings_.width, settings_.height, "globe-view", callbacks());
  } catch (const std::exception& e) {
    throw OutputError(std::string(e.what()) + "; pass --snapshot OUT.png to render headless");
  }
  scene_ = std::make_unique<TerrainScene>(settings_);
  const CameraPose start = scene_->initial_pose();
  const auto [data_lo, data_hi] = scene_->ramp().data_range();
  home_ = orbit_ = Orbit::from_pose(start, scene_->world(), (data_lo + data_hi) / 2);

  uint64_t events_seen = window_->events();
  const bool animate = settings_.flow_animate;
  while (!window_->should_close()) {
    if (frames_due_ > 0 || animate)
      window_->poll();
    else
      window_->wait(0.5);
    if (window_->events() != events_seen) {
      events_seen = window_->events();
      frames_due_ = kSettleFrames;
    }
    const auto now = std::chrono::steady_clock::now();
    if (now - last_title_ > kTitleEvery) {
      if (reload_edited_files()) frames_due_ = kSettleFrames;
      if (frames_due_ == 0 && !animate) last_title_ = now;
    }
    if (frames_due_ == 0 && !animate) continue;
    if (animate)  // a cycle of the flow pulses every 2 s
      scene_->settings().shading.flow_phase =
          std::fmod(std::chrono::duration<double>(now - opened_).count() / 2, 1.0);
    int w = 0, h = 0;
    window_->framebuffer_size(w, h);
    if (w > 0 && h > 0) draw(w, h);
  }
  return kExitOk;
}

void WindowSession::draw(int width, int height) {
  TerrainScene& s = *scene_;
  s.resize(width, height);
  const auto t0 = std::chrono::steady_clock::now();
  const FrameResult f = s.frame(orbit_.pose(s.world(), settings_.fov_y_deg), Loading::kAsReady,
                                TerrainScene::Output::kDraw);
  last_view_ = f.view;
  have_view_ = true;
  size_t waiting = f.selection.waiting;  // blocks and layer tiles not in yet
  for (const auto& layer : s.layers())
    waiting += layer->waiting();
  frames_due_ = waiting > 0 || s.loading() ? kSettleFrames : std::max(0, frames_due_ - 1);
  if (screenshot_pending_) {
    const std::string name = "globe-view-" + std::to_string(++screenshot_) + ".png";
    write_png(name, s.read_pixels(), width, height);
    std::fprintf(stderr, "globe-view: wrote %s\n", name.c_str());
    screenshot_pending_ = false;
  }
  blit_to_window(s.output_fbo(), s.renderer().width(), s.renderer().height(), width, height);
  window_->swap();
  // The title every 0.5 s, and on the last frame before the window sleeps.
  const auto drawn = std::chrono::steady_clock::now();
  if (drawn - last_title_ > kTitleEvery || frames_due_ == 0)
    set_title(f, std::chrono::duration<double, std::milli>(drawn - t0).count(), waiting);
}

void WindowSession::set_title(const FrameResult& f, double ms, size_t waiting) {
  TerrainScene& s = *scene_;
  char title[320];
  std::snprintf(title, sizeof title,
                "globe-view  %.1f ms (layers %.1f)  %zu patches  %zu k triangles  %zu blocks  "
                "waiting %zu",
                ms, std::accumulate(f.layer_ms.begin(), f.layer_ms.end(), 0.0), f.patches.size(),
                f.patches.size() * s.renderer().triangles_per_patch() / 1000,
                s.cache().stats().resident, waiting);
  if (const ImageLayers* im = s.images()) {
    const size_t n = std::strlen(title);
    std::snprintf(title + n, sizeof title - n, "  image %zu/%zu %s %.1f", layer_ + 1, im->size(),
                  im->visible(layer_) ? "opacity" : "hidden, opacity", im->opacity(layer_));
  }
  if (!picked_.empty()) {
    const std::string rest = title;
    std::snprintf(title, sizeof title, "globe-view  %s  %s", picked_.c_str(),
                  rest.c_str() + std::strlen("globe-view  "));
  }
  // The place whose chart is under the cursor.
  if (ChartLayer* charts = s.charts()) {
    const std::string place = charts->describe(int(last_x_), int(last_y_));
    if (!place.empty())
      std::snprintf(title, sizeof title, "globe-view  %s  waiting %zu", place.c_str(), waiting);
  }
  window_->set_title(title);
  last_title_ = std::chrono::steady_clock::now();
}

}  // namespace

int run_window(const ViewerSettings& settings) {
  return WindowSession(settings).run();
}

}  // namespace globe::viewer
