// The area fill pass (docs/viewer.md "Areas"): after the terrain and imagery,
// one full-screen pass over the G-buffer fills each pixel from its area
// tile's cell (area_shaders.hpp), no polygon draped as geometry, no shadow
// volume; the GPU reports which tiles its pixels wanted but did not find and
// which records it used, for the area cache.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "camera/camera.hpp"
#include "camera/layer_tiling.hpp"
#include "data/area_cache.hpp"
#include "render/gl_program.hpp"
#include "render/terrain_renderer.hpp"
#include "render/vector_pixel_glsl.hpp"

namespace globe::viewer {

// How one class of areas is drawn.
struct AreaStyle {
  glm::vec4 fill{0.5f, 0.5f, 0.5f, 0.75f};  // colour; alpha: its opacity over the image
  glm::vec3 outline{0.27f, 0.27f, 0.27f};
  float outline_px = 0.75f;  // 0: none
};

class AreaRenderer {
 public:
  AreaRenderer(uint64_t arena_words, int width, int height, CrsCross cross = CrsCross::kSame);
  ~AreaRenderer();
  AreaRenderer(const AreaRenderer&) = delete;
  AreaRenderer& operator=(const AreaRenderer&) = delete;

  void resize(int width, int height);
  void set_styles(const std::vector<AreaStyle>& classes);
  // Copies freshly loaded record `index`'s words into the arena.
  void upload(const AreaRecord& record);
  // Fills the areas over g's colour into output_fbo(); returns the GPU time
  // in ms and fills `feedback`.
  double draw(const GBuffer& g, const View& view, const WorldFrame& world, const AreaCache& cache,
              uint32_t frame, VectorFeedback& feedback);
  GLuint output_fbo() const { return fbo_; }
  GLuint output_texture() const { return output_; }
  // The polygon filled on top at pixel (x, y) (from the top-left) in the last
  // pass: its record and its polygon in that record's tile (both + 1; 0 =
  // none).
  std::pair<uint32_t, uint32_t> pick(int x, int y) const;
  void set_lens_only(float x, float y, float radius) { lens_only_ = {x, y, radius}; }

 private:
  void upload_tables(const AreaCache& cache);

  GlProgram program_;
  GLuint arena_ = 0, records_ = 0, table_ = 0, styles_ = 0, requests_ = 0, used_ = 0;
  GLuint vao_ = 0, fbo_ = 0, output_ = 0, pixel_record_ = 0, pixel_polygon_ = 0, timer_ = 0;
  uint32_t table_mask_ = 0, record_count_ = 0;
  int class_count_ = 0, width_ = 0, height_ = 0;
  CrsCross cross_;
  glm::vec3 lens_only_{0};
};

}  // namespace globe::viewer
