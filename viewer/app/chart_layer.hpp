// The charts of one view (docs/viewer.md "Charts"): a point package's tile
// cache, the tile selection for the view, the chart instances built from the
// selected tiles (sizes from the package's per-zoom statistics, colours from
// the style), optional collision thinning, the chart pass, the legend, and
// picking (which place is under a pixel).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/chart_style.hpp"
#include "app/line_layer.hpp"
#include "app/scene_layer.hpp"
#include "data/point_cache.hpp"
#include "render/chart_renderer.hpp"
#include "render/text_overlay.hpp"

namespace globe::viewer {

// Whether overlapping charts are all drawn or thinned out (larger first).
enum class ChartThinning { kOff, kOn };

struct ChartSettings {
  ChartKind kind = ChartKind::kPie;
  ChartDepth depth = ChartDepth::kTerrain;
  ChartThinning thinning = ChartThinning::kOff;
  std::optional<std::string> style;  // --chart-style file
  // --heatmap: a kernel density of the places instead of charts
  // (docs/viewer.md "Heatmaps"), weighted by a field or by "count" (the
  // source places each stands for); --heatmap-radius in pixels or metres.
  bool heatmap = false;
  std::string heat_field = "count";
  double heat_radius = 30;
  bool heat_radius_m = false;
  double heat_opacity = 0.75;
  std::optional<std::string> heat_colormap;  // --heatmap-colormap: a gdaldem colour file
};

struct ChartLayerStats {
  PointCacheStats cache;
  size_t tiles = 0, charts = 0, thinned = 0;
};

class ChartLayer final : public SceneLayer {
 public:
  static constexpr double kBudgetShare = 0.125;  // of the viewer's tile budget
  // Throws InputError for a bad style file, a package with more fields than
  // charts draw, or a chart kind that needs shares over a signed package.
  // cross and world: how the package's tiling maps to the terrain's frame.
  ChartLayer(PointPackage package, const ChartSettings& settings, uint64_t budget_bytes, int width,
             int height, CrsCross cross, const WorldFrame& world);
  ~ChartLayer() override;

  void resize(int width, int height) override {
    renderer_.resize(width, height), width_ = width, height_ = height;
  }
  // The chart pass over the image so far (the terrain, imagery and lines),
  // lit by the sun; Loading::kSettle waits for every selected tile. Returns
  // the GPU time of the charts in ms.
  double draw(const LayerPass& pass) override;
  GLuint output_fbo() const override { return renderer_.output_fbo(); }
  GLuint output_texture() const override { return renderer_.output_texture(); }
  // describe(x, y); highlight is not used.
  bool picks() const override { return true; }
  std::string pick(int x, int y, bool highlight) override {
    (void)highlight;
    return describe(x, y);
  }

  // The place whose chart covers pixel (x, y) (from the top-left) in the
  // last frame: "label: field value, ..." ("" for none).
  std::string describe(int x, int y);
  const char* pick_kind() const override { return "chart"; }
  // {"id", "count", "values": {field: value}} of that place.
  std::string pick_json(int x, int y) override;

  ChartKind kind() const { return settings_.kind; }
  // The charts of the last frame as discs for the labels to keep clear of
  // (docs/labels.md): each place's key point and the radius its chart
  // reaches on screen (none for a heatmap).
  struct Mark {
    int32_t key[2];
    float frac[2];
    float radius_px;
  };
  std::vector<Mark> marks() const;
  // Cycles pie, bar, stacked, column (skipping those the values cannot show).
  void next_kind();
  // Re-reads the style file if it changed (always: even if not); a broken
  // file keeps the current style (the error goes to stderr).
  bool reload_style(bool always) override;  // true: the style changed
  ChartLayerStats stats() const;
  bool loading() override { return cache_.loader_busy(); }  // tiles still being read
  std::string stats_json(double ms) const override;
  std::vector<glm::vec4> overlay_boxes() const override {
    if (overlay_.drawn_bounds() == glm::vec4(0)) return {};
    return {overlay_.drawn_bounds()};
  }

 private:
  struct PlaceRef {
    tileformat::TileId tile;
    uint32_t index;
  };
  void build(const std::vector<tileformat::TileId>& tiles, const View& view,
             const WorldFrame& world);
  // The heatmap's instances: every place's ground point, weight and kernel radius.
  void build_heat(const std::vector<tileformat::TileId>& tiles, const View& view,
                  const WorldFrame& world);
  void sort_back_to_front(const View& view, const WorldFrame& world);
  void thin(const View& view, const WorldFrame& world);
  void queue_legend();

  PointCache cache_;
  ChartSettings settings_;
  ChartStyle style_;
  std::filesystem::file_time_type style_time_{};
  ChartRenderer renderer_;
  TextOverlay overlay_;
  std::unique_ptr<tileformat::PackageReader> labels_;  // the features table, for picking
  std::vector<tileformat::TileId> roots_;
  LayerTiling tiling_;
  int heat_field_ = -1;                    // the field weighting the heatmap (-1: the count)
  double ground_per_m_ = 1;                // the last heatmap's ground units per metre
  HeatmapStyle heat_style_;                // its opacity and colours
  std::vector<tileformat::TileId> drawn_;  // the tiles of the instances
  std::vector<ChartInstance> instances_;
  std::vector<PlaceRef> places_;  // per instance
  bool dirty_ = true;
  int width_ = 0, height_ = 0;
  size_t thinned_ = 0;
};

}  // namespace globe::viewer
