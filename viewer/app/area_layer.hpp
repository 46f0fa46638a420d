// The areas of one view (docs/viewer.md "Areas"): an area package's tile
// cache, its classes' fills and outlines (the choropleth's colours, or the
// style classes' colours and casings) and the fill pass that draws them per
// pixel over the terrain and imagery, under lines and charts; picking: the
// feature whose polygon is filled at a pixel; a choropleth's legend.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/scene_layer.hpp"
#include "data/area_cache.hpp"
#include "render/area_renderer.hpp"
#include "render/text_overlay.hpp"

namespace globe::viewer {

class AreaLayer final : public SceneLayer {
 public:
  static constexpr double kBudgetShare = 0.15;  // of the viewer's tile budget
  // opacity: the fills' (times a style class's own).
  AreaLayer(const std::string& path, AreaPackage package, double opacity, uint64_t budget_bytes,
            int width, int height, CrsCross cross = CrsCross::kSame);

  void resize(int width, int height) override {
    renderer_.resize(width, height);
    width_ = width, height_ = height;
  }
  double draw(const LayerPass& pass) override;
  GLuint output_fbo() const override { return renderer_.output_fbo(); }
  GLuint output_texture() const override { return renderer_.output_texture(); }
  bool loading() override { return cache_.loader_busy(); }
  std::string stats_json(double ms) const override;
  std::vector<glm::vec4> overlay_boxes() const override {
    if (overlay_.drawn_bounds() == glm::vec4(0)) return {};
    return {overlay_.drawn_bounds()};
  }
  bool picks() const override { return true; }
  // "area ID (LAYER): {attributes}" of the polygon filled at (x, y), "" if none.
  std::string pick(int x, int y, bool highlight) override;
  const char* pick_kind() const override { return "area"; }
  // {"id", "layer", "attributes"} (docs/viewer.md "--pick-format json").
  std::string pick_json(int x, int y) override;
  // The feature id filled at (x, y) in the last frame, if any.
  std::optional<uint64_t> feature_at(int x, int y) const;
  // The feature's layer and attributes (JSON), from the features table.
  std::pair<std::string, std::string> feature_record(uint64_t id) const;

 private:
  size_t upload_loaded();
  void queue_legend();

  std::string path_;
  std::unique_ptr<tileformat::TileReader> features_;  // its own connection, for picking
  AreaCache cache_;
  AreaRenderer renderer_;
  std::vector<AreaStyle> styles_;
  uint32_t frame_ = 0;
  size_t tiles_used_ = 0;
  int width_ = 0, height_ = 0;
  TextOverlay overlay_;
};

}  // namespace globe::viewer
