// The line pass (docs/viewer.md "Lines"): after the terrain pass, draws the
// resident line tiles over the terrain image into its own output image.
//  - deferred (default): one full-screen pass reads the G-buffer and shades
//    each pixel from its line tile's cluster cell (line_shaders.hpp);
//  - geometry: the baseline, the same tiles' segments as draped quads;
//  - lifted (--bundles 3d): the same tiles' segments as quads lifted above
//    the terrain, on the flat frame or the globe.
// Either way the GPU reports which tiles its pixels wanted but did not find
// (requests) and which records it used, for the line cache.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "camera/camera.hpp"
#include "camera/layer_tiling.hpp"
#include "data/line_cache.hpp"
#include "render/gl_program.hpp"
#include "render/terrain_renderer.hpp"
#include "render/vector_pixel_glsl.hpp"
#include "runtime/line_style.hpp"

namespace globe::viewer {

enum class LineMode { kDeferred, kGeometry, kLifted };

// The terrain data the geometry baseline drapes its lines on (and lifted
// lines rise from).
struct TerrainHeights {
  GLuint texture = 0;                                     // R32F layers
  std::vector<std::pair<tileformat::TileId, int>> slots;  // resident block -> layer
  int min_zoom = 0, max_zoom = 0, block_size = 0;
  const TerrainRenderer* frame = nullptr;  // lifted: sets the frame's uniforms
  double lift_m = 0;                       // lifted: metres above the terrain
  double error_px = 0;      // lifted: the terrain LOD's screen-space error bound, cleared too
  double relief_world = 0;  // heatmaps: the terrain's height range, world units
};

// A class coloured by the ground under it: the G-buffer value it reads
// (1 slope in degrees, 2 height in metres), the values at the ends of its
// ramp and kEntries colours evenly between them.
struct LineRamp {
  static constexpr int kEntries = 256;
  int by = 0;  // 0: the class's plain colour
  float lo = 0, hi = 1;
  std::vector<uint8_t> rgba;  // kEntries * 4
};

using LineFeedback = VectorFeedback;

class LineRenderer {
 public:
  // arena_words: capacity of the tile arena (the line cache's budget).
  // cross: how the terrain's CRS reaches the line tiling's (deferred lines
  // only; the geometry and lifted modes need the terrain's tiling).
  LineRenderer(uint64_t arena_words, int width, int height, CrsCross cross = CrsCross::kSame);
  ~LineRenderer();
  LineRenderer(const LineRenderer&) = delete;
  LineRenderer& operator=(const LineRenderer&) = delete;

  void resize(int width, int height);
  // ramps: per class (may be shorter: the rest keep their plain colours).
  void set_styles(const std::vector<NamedLineStyle>& classes,
                  const std::vector<LineRamp>& ramps = {});
  // Copies freshly loaded record `index`'s words into the arena (and keeps
  // its segments' classes, for lifted lines).
  void upload(uint32_t index, const LineRecord& record);
  // Draws the lines over g's colour into output_fbo(); returns the GPU time
  // of the line work in ms (geometry mode: the quads alone, not the tile
  // selection pass) and fills `feedback`.
  double draw(const GBuffer& g, const View& view, const WorldFrame& world, double exaggeration,
              const LineCache& cache, const TerrainHeights& terrain, LineMode mode, uint32_t frame,
              LineFeedback& feedback);
  GLuint output_fbo() const { return fbo_; }
  GLuint output_texture() const { return output_; }
  // A magic lens showing the lines (deferred mode): only inside the circle
  // (centre in pixels from the top-left); radius 0: everywhere.
  void set_lens_only(float x, float y, float radius) { lens_only_ = {x, y, radius}; }
  // The line drawn on top at pixel (x, y) (from the top-left) in the last
  // deferred pass: its record and its segment in that record's tile (both
  // + 1; 0 = no line there, or the geometry baseline).
  std::pair<uint32_t, uint32_t> pick(int x, int y) const;

 private:
  void upload_tables(const LineCache& cache);
  void read_feedback(const LineCache& cache, uint32_t frame, LineFeedback& feedback);
  // The resident terrain blocks' hash table, bound; returns its mask.
  uint32_t upload_terrain_table(const TerrainHeights& terrain);
  void draw_geometry(const View& view, const WorldFrame& world, double exaggeration,
                     const LineCache& cache, const TerrainHeights& terrain, GLuint depth,
                     const std::vector<uint32_t>& used);
  void draw_lifted(const View& view, const WorldFrame& world, double exaggeration,
                   const LineCache& cache, const TerrainHeights& terrain, GLuint depth,
                   const std::vector<uint32_t>& used, uint32_t frame);

  GlProgram deferred_, geometry_, lifted_points_, lifted_;
  GLuint ramps_ = 0;  // RGBA8, LineRamp::kEntries x one row per ramp
  int ramp_rows_ = 0;
  GLuint arena_ = 0, records_ = 0, table_ = 0, styles_ = 0, requests_ = 0, used_ = 0,
         terrain_table_ = 0;
  // fbo_: output + pixel records (the full-screen pass); geometry_fbo_:
  // output + the terrain's depth (the baseline's quads).
  GLuint vao_ = 0, fbo_ = 0, geometry_fbo_ = 0, output_ = 0, pixel_record_ = 0, pixel_segment_ = 0,
         timer_ = 0;
  uint32_t table_mask_ = 0, record_count_ = 0;
  int class_count_ = 0, width_ = 0, height_ = 0;
  CrsCross cross_;
  glm::vec3 lens_only_{0};
  std::vector<int> lifted_order_;  // the classes lifted lines draw, bottom first
  // Lifted lines: per record, its segments' classes; the frame's lifted
  // points and its (first point, class) items, grouped by class.
  std::unordered_map<uint32_t, std::vector<uint16_t>> segment_classes_;
  GLuint points_ = 0, items_ = 0;
  size_t points_capacity_ = 0;
};

}  // namespace globe::viewer
