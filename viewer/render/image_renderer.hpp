// The imagery pass (docs/viewer.md "Imagery", image_shaders.hpp): after the
// terrain pass, drapes the image layers over the terrain image into its own
// output image, which the line pass then draws over. Each layer's tiles live
// in a texture array (one slot per layer of it, with mips); the GPU reports
// the tiles its pixels wanted but did not find and the slots it read.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "camera/camera.hpp"
#include "data/image_cache.hpp"
#include "render/gl_program.hpp"
#include "render/terrain_renderer.hpp"

namespace globe::viewer {

// How a layer's pixels find their image coordinates this frame (computed
// on the CPU from the view origin; see image_shaders.hpp).
struct ImageLayerFrame {
  enum Mode : int { kSameCrs = 0, kGeodeticToMercator = 1, kMercatorToGeodetic = 2, kGrid = 3 };
  int mode = kSameCrs;
  glm::ivec2 base{0};     // reference-zoom tile of the anchor
  glm::vec2 frac{0};      // the anchor inside it
  glm::vec2 per_unit{0};  // reference-zoom tiles per image CRS unit
  int ref_zoom = 0;
  glm::vec2 param{0};     // kGeodeticToMercator: (lat0 rad, R); kMercatorToGeodetic: (y0 / R, R)
  glm::vec2 grid_org{0};  // kGrid: the view origin in grid cells
  glm::vec2 grid_inv_cell{0};
  float opacity = 1;
};

enum class ImageLighting { kHillshade, kUnlit };

struct ImageFeedback {
  std::vector<std::vector<tileformat::TileId>> requests;  // per layer
  std::vector<std::vector<uint32_t>> used;                // per layer: slots read
};

class ImageRenderer {
 public:
  // grid_n: samples per side of the kGrid mapping grids.
  ImageRenderer(int width, int height, int grid_n);
  ~ImageRenderer();
  ImageRenderer(const ImageRenderer&) = delete;
  ImageRenderer& operator=(const ImageRenderer&) = delete;

  void resize(int width, int height);
  // Adds a layer whose tiles `cache` holds (its texture array is made here);
  // `grid`: its kGrid mapping (grid_n^2 x, y pairs, rows from the north), or
  // empty. At most shaders::kMaxImageLayers layers.
  void add_layer(const ImageCache& cache, const std::vector<float>& grid);
  void upload(size_t layer, uint32_t slot, const ImageMips& mips);
  // Composites the layers over g's colour into output_texture(); returns the
  // GPU time in ms.
  double draw(const GBuffer& g, const View& view, const WorldFrame& world,
              const std::vector<const ImageCache*>& caches,
              const std::vector<ImageLayerFrame>& frames, ImageLighting lighting, float light_norm,
              uint32_t frame, ImageFeedback& feedback);
  GLuint output_fbo() const { return fbo_; }
  GLuint output_texture() const { return output_; }
  // A magic lens showing the images: only inside the circle (centre in
  // pixels from the top-left); radius 0: everywhere.
  void set_lens_only(float x, float y, float radius) { lens_only_ = {x, y, radius}; }

 private:
  struct Layer {
    GLuint texture = 0;
    int slots = 0, min_zoom = 0, max_zoom = 0, tile_px = 256;
  };
  GlProgram program_;
  std::vector<Layer> layers_;
  std::vector<std::vector<float>> grids_;
  int grid_n_;
  GLuint grids_texture_ = 0;
  bool grids_dirty_ = true;
  GLuint tables_ = 0, requests_ = 0, used_ = 0, vao_ = 0, fbo_ = 0, output_ = 0, timer_ = 0;
  int width_ = 0, height_ = 0;
  glm::vec3 lens_only_{0};
};

}  // namespace globe::viewer
