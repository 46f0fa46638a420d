// The image layers of one view (docs/viewer.md "Imagery"): their caches,
// how each maps the terrain's tiling onto its own (chosen once: the same
// CRS, geodetic <-> webmercator in closed form, or a grid computed with PROJ
// over the image's footprint), their opacities, and the imagery pass.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "app/scene_layer.hpp"
#include "camera/world_frame.hpp"
#include "data/image_cache.hpp"
#include "render/image_renderer.hpp"

namespace globe::viewer {

class ImageLayers final : public SceneLayer {
 public:
  static constexpr double kBudgetShare = 0.25;  // of the viewer's tile budget
  // Opens the image packages (bottom first) and checks each against the
  // terrain; throws InputError naming the file, warns of an image whose
  // bounds miss `terrain_lonlat` (when known). budget_bytes is shared by all
  // layers. An OpenGL context must be current.
  ImageLayers(const std::vector<std::string>& paths, const std::vector<double>& opacities,
              const WorldFrame& world, const tileformat::Bounds* terrain_lonlat,
              uint64_t budget_bytes, int width, int height);
  ~ImageLayers() override;

  size_t size() const { return layers_.size(); }
  void resize(int width, int height) override { renderer_.resize(width, height); }
  double opacity(size_t i) const { return layers_[i].opacity; }
  void set_opacity(size_t i, double v);
  bool visible(size_t i) const { return layers_[i].visible; }
  void set_visible(size_t i, bool v) { layers_.at(i).visible = v; }
  // Draws the imagery over the image so far, lit by the sun (unlit with
  // --shading imagery), inside the lens if it shows images; Loading::kSettle
  // keeps loading until no visible tile is missing. Returns the GPU time of
  // the last pass in ms.
  double draw(const LayerPass& pass) override;
  GLuint output_fbo() const override { return renderer_.output_fbo(); }
  GLuint output_texture() const override { return renderer_.output_texture(); }
  bool loading() override;
  size_t waiting() const override;
  std::string stats_json(double ms) const override;
  std::vector<ImageCacheStats> stats() const;
  int passes() const { return passes_; }  // imagery passes the last draw took

 private:
  struct Layer {
    std::unique_ptr<ImageCache> cache;
    int mode = ImageLayerFrame::kSameCrs;
    double opacity = 1;
    bool visible = true;
    // kGrid: the grid's north-west corner and cell size (terrain CRS) and
    // the image CRS point its values are relative to.
    glm::dvec2 grid_nw{0}, grid_cell{1}, grid_anchor{0};
  };
  ImageLayerFrame frame_of(const Layer& l, const View& view, const WorldFrame& world) const;
  size_t upload_loaded();

  std::vector<Layer> layers_;
  ImageRenderer renderer_;
  uint32_t frame_ = 0;
  int passes_ = 0;
};

}  // namespace globe::viewer
