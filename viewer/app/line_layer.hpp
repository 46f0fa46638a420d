// The lines of one view: a line package's tile cache, its styles (from the
// package, optionally overridden by a style file that can be reloaded while
// the window is open) and the line pass that draws them over the terrain;
// picking: the feature under a pixel, drawn highlighted from then on (for a
// bundled-flows package, every connection through the picked bundle); a
// bundled-flows package's legend of weight classes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/bundle_legend.hpp"
#include "app/heat_samples.hpp"
#include "app/scene_layer.hpp"
#include "data/line_cache.hpp"
#include "render/chart_renderer.hpp"
#include "render/line_renderer.hpp"
#include "runtime/line_style.hpp"

namespace globe::viewer {

struct LineLayerStats {
  LineCacheStats cache;
  size_t tiles_used = 0;  // records the last frame read
};

class LineLayer final : public SceneLayer {
 public:
  static constexpr double kBudgetShare = 0.25;  // of the viewer's tile budget
  // Throws InputError if the style file is unreadable or wrong.
  // cross: how the terrain's CRS reaches the package's tiling; lines in
  // another tiling draw per pixel only (LineMode::kDeferred).
  LineLayer(const std::string& path, LinePackage package, std::optional<std::string> style_path,
            LineMode mode, uint64_t budget_bytes, int width, int height,
            CrsCross cross = CrsCross::kSame);

  void resize(int width, int height) override {
    renderer_.resize(width, height);
    if (heat_) heat_->resize(width, height);
    width_ = width, height_ = height;
  }
  // The line pass over the image so far (inside the lens if it shows lines;
  // classes coloured by height over pass.height_lo..hi); Loading::kSettle:
  // keep loading until no visible tile is missing (headless). Returns the GPU
  // time of the last pass in ms. With a heatmap, its colours go over the
  // image so far instead of the lines.
  double draw(const LayerPass& pass) override;
  GLuint output_fbo() const override {
    return heat_ ? heat_->output_fbo() : renderer_.output_fbo();
  }
  GLuint output_texture() const override {
    return heat_ ? heat_->output_texture() : renderer_.output_texture();
  }
  // A heatmap of the lines instead of the lines (docs/viewer.md "Heatmaps"):
  // the density of their length, weighted by the bundle weight classes'
  // middles (a bundled-flows package) or 1.
  void enable_heatmap(const HeatRadius& radius, const HeatmapStyle& style, const WorldFrame& world);
  // Re-reads the style file if it changed since the last read (always: even
  // if not). A broken file keeps the current styles; the error goes to stderr.
  bool reload_style(bool always) override;  // true: the styles changed
  LineMode mode() const { return mode_; }
  // Keeps the mode (and says so on stderr) where the lines cannot be drawn
  // in `m`: geometry and lifted lines need the terrain's tiling.
  void set_mode(LineMode m);
  LineLayerStats stats() const { return {cache_.stats(), tiles_used_}; }
  bool loading() override { return cache_.loader_busy(); }  // tiles still being read
  std::string stats_json(double ms) const override;
  std::vector<glm::vec4> overlay_boxes() const override {
    if (overlay_.drawn_bounds() == glm::vec4(0)) return {};
    return {overlay_.drawn_bounds()};
  }

  // The line drawn on top at pixel (x, y) (from the top-left) in the last
  // frame: "" where there is none (deferred mode only). Otherwise its
  // description, and the frames that follow highlight it; in a bundled-flows
  // package (tileformat §7.5) a bundle highlights every bundle of the
  // connections through it. Picking where no line is clears the highlight.
  // highlight false: only the description (picks that read one frame).
  bool picks() const override { return true; }
  std::string pick(int x, int y, bool highlight) override;
  bool picked_highlight() const override { return !highlighted_.empty(); }
  const char* pick_kind() const override { return "line"; }
  // {"id", "layer", "attributes"} of the line drawn on top there.
  std::string pick_json(int x, int y) override;
  // The feature ids drawn highlighted (sorted; empty: none).
  const std::vector<uint64_t>& highlighted() const { return highlighted_; }

 private:
  // Bundles and connections of a bundled-flows package, from its features
  // table (read on the first pick).
  struct BundleIndex {
    std::map<uint64_t, std::vector<uint64_t>> connections_of;  // bundle -> connections
    std::map<uint64_t, std::vector<uint64_t>> bundles_of;      // connection -> bundles
  };
  std::vector<NamedLineStyle> read_styles() const;
  // The terrain's height range (metres): where the built-in height ramp and a
  // colour file's percentages lie for classes coloured by height.
  void set_height_range(double lo, double hi);
  size_t upload_loaded();
  std::optional<uint64_t> feature_at(int x, int y);
  double draw_heatmap(const GBuffer& g, const View& view, const WorldFrame& world,
                      double exaggeration, const TerrainHeights& terrain, GLuint under_fbo);
  // The picked feature's description; adds the features it highlights
  // besides itself to `lit`.
  std::string describe(uint64_t feature, std::vector<uint64_t>& lit);
  const BundleIndex& bundle_index();

  std::string path_;
  std::optional<std::string> style_path_;
  std::filesystem::file_time_type style_time_{};
  std::vector<NamedLineStyle> package_styles_;
  bool bundled_ = false;                              // a §7.5 package
  std::unique_ptr<tileformat::TileReader> features_;  // tiles and features table, for picking
  std::unique_ptr<BundleIndex> bundles_;
  std::vector<uint64_t> highlighted_;
  LineMode mode_;
  LineCache cache_;
  LineRenderer renderer_;
  CrsCross cross_;
  std::unique_ptr<ChartRenderer> heat_;  // the heatmap, when enabled
  std::unique_ptr<LayerTiling> heat_tiling_;
  HeatRadius heat_radius_;
  HeatmapStyle heat_style_;
  double heat_ground_per_m_ = 1;
  std::vector<uint32_t> used_;  // the records the last frame read
  uint32_t frame_ = 0;
  size_t tiles_used_ = 0;
  int width_ = 0, height_ = 0;
  std::vector<NamedLineStyle> styles_;          // as drawn (package, style file, highlight)
  std::pair<double, double> heights_{0, 3000};  // set_height_range
  std::vector<LegendRow> legend_;               // bundled flows: the weight classes
  TextOverlay overlay_;
};

}  // namespace globe::viewer
