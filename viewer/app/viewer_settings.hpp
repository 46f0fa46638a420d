// globe-view's command line, parsed into one Settings struct (no work here).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/chart_layer.hpp"
#include "app/label_settings.hpp"
#include "camera/camera.hpp"
#include "data/network.hpp"
#include "render/line_renderer.hpp"
#include "render/terrain_renderer.hpp"

namespace globe::viewer {

inline constexpr double kGlobeDefaultSpanDeg = 30;

struct ViewerSettings {
  std::vector<std::string> packages;
  std::optional<std::string> snapshot;     // PNG path: render headless and exit
  std::optional<std::string> export_mesh;  // PLY path
  bool stats = false;
  // --pick X,Y or @LON,LAT (repeatable): describe what is drawn there.
  struct PickAt {
    bool geographic = false;  // a, b: lon, lat (degrees) or pixel x, y
    double a = 0, b = 0;
  };
  std::vector<PickAt> picks;
  int width = 1280, height = 720;
  std::optional<CameraPose> camera;
  std::vector<CameraPose> camera_path;  // --camera-path: one pose per line
  double fov_y_deg = 45;
  double max_error_px = 1.5;
  uint64_t cache_mb = 512;
  ShadingSettings shading;
  std::string platform = "auto";  // auto | osmesa | egl | glfw
  int frames = 5;                 // frames measured for --stats
  bool cull = true;
  // --globe / --flat; unset: the globe for geodetic and webmercator packages
  // whose data spans more than kGlobeDefaultSpanDeg (and not --lines geometry).
  std::optional<bool> globe;
  std::optional<std::string> style;  // line style file (JSON)
  LineMode line_mode = LineMode::kDeferred;
  std::optional<double> lift_m;  // --lift: lifted lines' height above the terrain (unset: auto)
  bool lines = true;             // --lines off: draw none
  bool imagery_unlit = false;    // --shading imagery
  bool flow_animate = false;     // --flow-animate: the window moves the flow pulses
  std::vector<double> image_opacity;  // --image-opacity, per image layer (the last repeats)
  double area_opacity = 0.75;         // --area-opacity: the area fills'
  bool pick_json = false;             // --pick-format json
  ChartSettings charts;               // --chart, --chart-style, --chart-depth, --chart-thinning
  bool charts_given = false;          // any of those options
  LabelSettings labels;               // --labels, --label-size, --label-font
  std::optional<std::string> labels_json;  // --labels-json FILE
  bool lens_mode_given = false;            // --lens named its mode
  NetworkSettings network;  // --cache-dir, --http-cache-mb, --offline, --max-connections

  bool headless() const {
    return snapshot || export_mesh || stats || !picks.empty() || labels_json ||
           platform == "osmesa" || platform == "egl";
  }
};

// Returns nullopt after printing --help. Throws UsageError.
std::optional<ViewerSettings> parse_viewer_settings(const std::vector<std::string>& args);

}  // namespace globe::viewer
