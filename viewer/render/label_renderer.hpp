// The label passes (docs/viewer.md "Labels", label_shaders.hpp): where on
// screen the labels' ground points land (on the terrain as drawn), how far
// the terrain is at the pixels a label covers (its occlusion test against
// the G-buffer), and the glyphs over the finished image into an output image
// of its own. The CPU decides in between (app/label_layer.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include "camera/camera.hpp"
#include "render/gl_program.hpp"
#include "render/line_renderer.hpp"
#include "render/terrain_renderer.hpp"

namespace globe::viewer {

// A ground point a label needs: absolute key units.
struct LabelProbe {
  int32_t key[2];
  float frac[2];
};

// Where it landed.
struct ProbeResult {
  float x = 0, y = 0;  // pixels from the top-left
  float distance = 0;  // world units from the eye
  bool front = false;  // in front of the eye and on the near side of the globe
};

// One glyph: a quad about its pivot.
struct GlyphQuad {
  float pivot[4];  // x, y (px from the top-left), angle (radians, clockwise on screen), scale (px
                   // per texel)
  float rect[4];   // x0, y0, x1, y1 around the pivot before rotation (px, y down)
  float atlas[4];  // texels x0, y0, x1, y1
  float style[4];  // alpha, halo (px), -, -
};

struct LabelColors {
  glm::vec3 fill{0.10f, 0.10f, 0.12f};
  glm::vec3 halo{1.0f, 1.0f, 1.0f};
};

class LabelRenderer {
 public:
  LabelRenderer(int width, int height);
  ~LabelRenderer();
  LabelRenderer(const LabelRenderer&) = delete;
  LabelRenderer& operator=(const LabelRenderer&) = delete;

  void resize(int width, int height);
  // The probes to project each frame (they change only when labels load).
  void set_probes(const std::vector<LabelProbe>& probes);
  // Projects every probe with the frame's terrain heights.
  std::vector<ProbeResult> project(const View& view, const WorldFrame& world,
                                   const TerrainRenderer& terrain, const TerrainHeights& heights,
                                   double exaggeration);
  // The same for points of this frame only (the charts' places).
  std::vector<ProbeResult> project(const std::vector<LabelProbe>& points, const View& view,
                                   const WorldFrame& world, const TerrainRenderer& terrain,
                                   const TerrainHeights& heights, double exaggeration);
  // The distance from the eye to the terrain at each pixel (x, y from the
  // top-left) of the G-buffer: -1 where there is none (sky), -2 off screen.
  std::vector<float> terrain_distances(const std::vector<float>& pixels_xy, const GBuffer& g,
                                       const View& view);
  // The atlas image (single channel, top row first), rows [y0, y1) changed.
  void upload_atlas(const uint8_t* pixels, int width, int height, int y0, int y1);
  // Copies `input_fbo`'s colour into the output and draws the glyphs over
  // it; returns the GPU time in ms.
  double draw(GLuint input_fbo, const std::vector<GlyphQuad>& glyphs, const LabelColors& colors);
  GLuint output_fbo() const { return fbo_; }
  GLuint output_texture() const { return color_; }

 private:
  // Renders `count` points of `vao` with `p` into a float image `row` texels
  // wide and reads it back.
  std::vector<float> run_points(const GlProgram& p, GLuint vao, size_t count, int channels);
  // Projects the `count` probes of `vao`.
  std::vector<ProbeResult> run_probes(GLuint vao, size_t count, const View& view,
                                      const WorldFrame& world, const TerrainRenderer& terrain,
                                      const TerrainHeights& heights, double exaggeration);

  int width_ = 0, height_ = 0;
  GlProgram probe_, depth_, glyph_;
  GLuint probe_vao_ = 0, probe_vbo_ = 0, depth_vao_ = 0, depth_vbo_ = 0;
  GLuint extra_vao_ = 0, extra_vbo_ = 0;
  GLuint glyph_vao_ = 0, corner_vbo_ = 0, glyph_vbo_ = 0, terrain_table_ = 0;
  GLuint result_ = 0, result_fbo_ = 0;
  int result_w_ = 0, result_h_ = 0;
  GLuint atlas_ = 0;
  int atlas_w_ = 0, atlas_h_ = 0;
  GLuint fbo_ = 0, color_ = 0, timer_ = 0;
  size_t probes_ = 0;
};

}  // namespace globe::viewer
