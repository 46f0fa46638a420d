// The chart pass (docs/viewer.md "Charts"): after the terrain, imagery and
// line passes, draws one chart per instance over the finished image into
// its own output image, in one instanced draw (chart_shaders.hpp):
// sprites (pie, bar, stacked bar) or 3D columns. Depth-tested against the
// terrain's depth (ChartDepth::kTerrain) or drawn over it (kOnTop). A second
// attachment keeps, per pixel, the pick id of the chart drawn there.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "camera/camera.hpp"
#include "render/gl_program.hpp"
#include "render/line_renderer.hpp"
#include "render/terrain_renderer.hpp"

namespace globe::viewer {

enum class ChartKind { kPie, kBar, kStacked, kColumn };
enum class ChartDepth { kTerrain, kOnTop };

inline constexpr int kMaxChartFields = 16;

// One chart, as the vertex shader reads it.
struct ChartInstance {
  int32_t key[2];  // absolute key units of the place: the integer part
  float frac[2];   // and the fraction (a key unit is a finest terrain sample)
  // pie: diameter px, -, -, -; bar: -, px per value unit, bar width px, -;
  // stacked: -, px per value unit, width px, -; column: footprint (world
  // units), world units per value unit, -, -.
  float params[4];
  float values[kMaxChartFields];
  uint32_t pick;  // index + 1
  uint32_t pad;
};
static_assert(sizeof(ChartInstance) == 104, "the vertex layout of chart_renderer.cpp");

// The heatmap drawn instead of charts (instances' params: ground x, y
// relative to the view origin, weight, kernel radius in ground units).
struct HeatmapStyle {
  float opacity = 0.75f;
  float margin_world = 0;     // world units the relief may move a ground point on screen
  std::vector<uint8_t> ramp;  // 256 RGBA entries over 0..the largest density; empty: YlOrRd
};

struct ChartDrawStyle {
  ChartKind kind = ChartKind::kPie;
  ChartDepth depth = ChartDepth::kTerrain;
  int fields = 1;
  std::array<glm::vec4, kMaxChartFields> colors{};
  glm::vec4 outline{0.1f, 0.1f, 0.1f, 1.0f};  // rgb, width in px (0: none)
  float opacity = 1;
};

class ChartRenderer {
 public:
  ChartRenderer(int width, int height);
  ~ChartRenderer();
  ChartRenderer(const ChartRenderer&) = delete;
  ChartRenderer& operator=(const ChartRenderer&) = delete;

  void resize(int width, int height);
  // Replaces the instances (drawn in this order: back to front).
  void set_instances(const std::vector<ChartInstance>& instances);
  // Copies `input_fbo`'s colour into the output, then draws the charts over
  // it; `terrain` gives the frame's uniforms and the height blocks
  // `heights` lists. Returns the GPU time of the charts in ms. Column
  // charts write the terrain's depth buffer.
  double draw(GLuint input_fbo, const GBuffer& g, const View& view, const WorldFrame& world,
              const TerrainRenderer& terrain, const TerrainHeights& heights,
              const ChartDrawStyle& style, double exaggeration, glm::vec3 sun);
  // The heatmap of the instances instead (heatmap_shaders.hpp): their
  // kernel density over `input_fbo`'s colour, its top colour at the
  // frame's largest density. Returns the GPU time in ms.
  double draw_heatmap(GLuint input_fbo, const GBuffer& g, const View& view, const WorldFrame& world,
                      const TerrainRenderer& terrain, const TerrainHeights& heights,
                      const HeatmapStyle& style, double exaggeration);
  GLuint output_fbo() const { return fbo_; }
  GLuint output_texture() const { return color_; }
  // The pick id under pixel (x, y) (y from the top) of the last draw; 0 for
  // none.
  uint32_t pick(int x, int y) const;
  // The last heatmap's density (weight per ground unit squared) at pixel
  // (x, y) (from the top-left), and its largest.
  float density_at(int x, int y) const;
  float density_top() const { return density_top_; }

 private:
  // Binds the terrain table and sets the uniforms the anchor code needs.
  void prepare(const GlProgram& p, const View& view, const WorldFrame& world,
               const TerrainRenderer& terrain, const TerrainHeights& heights, double exaggeration);
  // Copies input_fbo's colour into the output image.
  void copy_input(GLuint input_fbo);

  GlProgram sprite_, column_, heat_splat_, heat_color_;
  GLuint density_ = 0, density_fbo_ = 0, heat_vao_ = 0, heat_ramp_ = 0;
  float density_top_ = 0;
  GLuint fbo_ = 0, color_ = 0, picks_ = 0;
  GLuint sprite_vao_ = 0, column_vao_ = 0, corner_vbo_ = 0, box_vbo_ = 0, instance_vbo_ = 0;
  GLuint terrain_table_ = 0, timer_ = 0;
  GLsizei instances_ = 0;
  int width_ = 0, height_ = 0;
  GLuint bound_depth_ = 0;  // the depth texture attached to fbo_
};

}  // namespace globe::viewer
