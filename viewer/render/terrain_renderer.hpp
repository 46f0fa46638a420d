// The terrain pass: one terrain-independent lattice of L*L triangles (built
// once), drawn instanced for every selected patch into an offscreen
// framebuffer, heights fetched from the resident blocks' texture layers.
// Also captures the drawn triangles (transform feedback) for --export-mesh
// and reads the image back for snapshots.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "camera/camera.hpp"
#include "data/block_cache.hpp"
#include "render/color_ramp.hpp"
#include "render/gl_program.hpp"
#include "render/patch_selection.hpp"
#include "render/shading_modes.hpp"

namespace globe::viewer {

struct ShadingSettings {
  Shading mode = Shading::kHillshade;
  double sun_azimuth_deg = 315, sun_altitude_deg = 45;
  double exaggeration = 1;
  bool exaggeration_given = false;  // --exaggeration: no automatic relief stretch
  bool ambient_occlusion = false;   // multiply the sky-view factor onto the colour (and imagery)
  // The elevation ramp: a built-in name or a gdaldem color-relief file, over
  // the data's real heights (the coarsest blocks' samples, clipped to the
  // percentiles) unless height_range is given.
  std::string colormap = "hypsometric";
  bool colormap_given = false;  // --colormap: slope, skyview and flow use the ramp too
  std::optional<std::pair<double, double>> height_range;
  double height_percentile = 0;
  // Flow shading: pulses running downstream along the flow directions, at
  // this phase (cycles; the window advances it with --flow-animate); none
  // when unset.
  std::optional<double> flow_phase;
  // Isolines per pixel (--isolines): every `isoline_interval` metres of the
  // drawn heights (0: none), every `isoline_index`-th one bold (0: none), in
  // `isoline_rgb`; widths in pixels, whatever the distance or slope.
  double isoline_interval = 0;
  int isoline_index = 0;
  // What the isolines follow (--isolines-of): the heights (metres), the
  // slope (degrees) or the upstream area (log2 m^2, an analysis package's
  // flow_accumulation layer).
  enum class IsolinesOf { kHeight = 0, kSlope = 1, kFlow = 2 };
  IsolinesOf isolines_of = IsolinesOf::kHeight;
  std::array<float, 3> isoline_rgb{0.36f, 0.2f, 0.09f};
  // A magic lens (--lens): inside the screen circle (pixels from the
  // top-left) the terrain is shaded in `lens_mode` instead; radius 0: none.
  double lens_x = 0, lens_y = 0, lens_radius = 0;
  Shading lens_mode = Shading::kElevation;
  // What the lens shows: the terrain shaded in lens_mode, isolines every
  // lens_isoline_interval, or the line package or image layers only there.
  enum class LensShows { kShading = 0, kIsolines = 1, kLines = 2, kImages = 3 };
  LensShows lens_shows = LensShows::kShading;
  double lens_isoline_interval = 0;
};

// The terrain pass's output: shaded colour (RGBA8), world position (RGBA32F,
// metres from the view origin, w = 1 where terrain was drawn), the drawn
// triangle's normal (RGBA16F) and depth.
// The terrain pass's output, read by the deferred passes: colour; world
// position (w = 1 on terrain); the drawn triangle's plane; and the "ground"
// coordinates: the flat frame's x/y at the view latitude (world_frame.hpp;
// equal to the position's x/y on the flat frame, continuous across the
// antimeridian on the globe) with their screen derivatives, so imagery and
// lines find their tiles on either surface without inverting it.
struct GBuffer {
  GLuint fbo = 0, color = 0, position = 0, normal = 0, depth = 0;
  GLuint ground = 0;     // RGBA32F: ground x, y, d/dx of x, y (per pixel to the right)
  GLuint ground_dy = 0;  // RGBA32F: d/dy of ground x, y (per pixel up), height m, slope deg
  int width = 0, height = 0;
};

struct RenderTimes {
  double terrain_ms = 0;  // GPU time of the terrain pass
};

// One vertex of a captured triangle: world metres relative to view.origin
// (exactly what was drawn; shared vertices are bit-identical), its key point
// relative to view.origin and its height in metres (before exaggeration).
struct CapturedVertex {
  float world[3];
  int32_t key[2];
  float height_m;
};

class TerrainRenderer {
 public:
  // block_size: samples per block side; slots: texture layers (cache slots);
  // analysis: the blocks carry analysis texels (LoadedBlock::analysis).
  TerrainRenderer(int block_size, int lattice, int slots, int width, int height,
                  bool analysis = false);
  ~TerrainRenderer();
  TerrainRenderer(const TerrainRenderer&) = delete;
  TerrainRenderer& operator=(const TerrainRenderer&) = delete;

  void resize(int width, int height);
  void upload(const LoadedBlock& block);
  // The elevation ramp's lookup table (shading mode 1).
  void set_ramp(const RampTable& table);
  // Whether slope and aspect come from the analysis texels' gradient (the
  // package has both layers) or from the drawn heights.
  void set_gradient_from_layers(bool on) { gradient_from_layers_ = on; }
  // Per zoom: plan curvature x sample spacing where the edges shading saturates.
  void set_edge_scales(const std::array<float, 32>& scales) { edge_scales_ = scales; }
  // The hillshade's slope stretch per zoom (lighting only; app/relief_scale).
  void set_relief_stretches(const std::array<float, 32>& s) { relief_stretches_ = s; }
  // Where the built-in slope ramp ends (degrees) and the sky-view factor the
  // skyview mode draws black (app/data_ranges.hpp).
  void set_data_ranges(float slope_top_deg, float sky_low) {
    slope_top_deg_ = slope_top_deg, sky_low_ = sky_low;
  }
  // log2 of the upstream areas (m^2) where rivers start to show and where
  // they are darkest.
  void set_flow_range(float lo, float hi) { flow_lo_ = lo, flow_hi_ = hi; }
  // Draws into the offscreen framebuffer; waits for the GPU and returns its time.
  RenderTimes draw(const std::vector<Patch>& patches, const View& view, const WorldFrame& frame,
                   const ShadingSettings& shading);
  const GBuffer& gbuffer() const { return g_; }
  GLuint heights_texture() const { return heights_; }
  // Uses program `p` and sets the uniforms of shaders::kFrameWorldGlsl
  // (frame scales, globe anchor), u_view_proj, and u_heights (the heights
  // texture, bound to unit 0), for `view`.
  void set_frame_uniforms(const GlProgram& p, const View& view, const WorldFrame& frame,
                          double exaggeration) const;
  // The drawn triangles, 3 vertices each, as the vertex shader computed them.
  std::vector<CapturedVertex> capture_triangles(const std::vector<Patch>& patches, const View& view,
                                                const WorldFrame& frame, double exaggeration);
  size_t triangles_per_patch() const { return static_cast<size_t>(lattice_) * lattice_; }
  // Skirts: a wall hanging from every patch's rim, `fraction` of the patch's
  // leg deep (0: none, the default). For terrain whose blocks are not nested
  // (made from a remote source's tiles, which each zoom resamples on its own:
  // data/block_synthesizer.hpp), so that a patch beside one of the next zoom
  // shows no crack between them — CesiumJS's answer to the same problem.
  // Drawn only, never captured (--export-mesh gives the surface).
  void set_skirts(float fraction) { skirt_fraction_ = fraction; }
  int width() const { return g_.width; }
  int height() const { return g_.height; }

 private:
  void upload_instances(const std::vector<Patch>& patches, const View& view,
                        const WorldFrame& frame);

  int size_, lattice_, slots_;
  GLsizei index_count_ = 0, skirt_index_count_ = 0;
  float skirt_fraction_ = 0;
  GlProgram draw_program_, capture_program_;
  GLuint vao_ = 0, lattice_vbo_ = 0, index_buffer_ = 0, instance_buffer_ = 0;
  GLuint heights_ = 0, mask_ = 0, ramp_ = 0;
  GLuint layers_ = 0, flow_ = 0;  // 0 without analysis
  float flow_lo_ = 10, flow_hi_ = 20;
  double ramp_lo_ = 0, ramp_hi_ = 1;
  std::array<float, 32> edge_scales_;
  std::array<float, 32> relief_stretches_;
  float slope_top_deg_ = 45, sky_low_ = 0.65f;
  bool gradient_from_layers_ = false;
  GBuffer g_;
  GLuint timer_ = 0;
};

}  // namespace globe::viewer
