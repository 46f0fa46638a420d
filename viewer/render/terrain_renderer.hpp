// The terrain pass: one terrain-independent lattice of L*L triangles (built
// once), drawn instanced for every selected patch into an offscreen
// framebuffer, heights fetched from the resident blocks' texture layers.
// Also captures the drawn triangles (transform feedback) for --export-mesh
// and reads the image back for snapshots.
#pragma once

#include <cstdint>
#include <vector>

#include "camera/camera.hpp"
#include "data/block_cache.hpp"
#include "render/gl_program.hpp"
#include "render/patch_selection.hpp"

namespace globe::viewer {

enum class Shading { kHillshade = 0, kElevation = 1, kSlope = 2, kAspect = 3 };

struct ShadingSettings {
  Shading mode = Shading::kHillshade;
  double sun_azimuth_deg = 315, sun_altitude_deg = 45;
  double exaggeration = 1;
  double range_min_m = 0, range_max_m = 1000;  // elevation ramp
};

struct RenderTimes {
  double terrain_ms = 0;  // GPU time of the terrain pass
};

class TerrainRenderer {
 public:
  // block_size: samples per block side; slots: texture layers (cache slots).
  TerrainRenderer(int block_size, int lattice, int slots, int width, int height);
  ~TerrainRenderer();
  TerrainRenderer(const TerrainRenderer&) = delete;
  TerrainRenderer& operator=(const TerrainRenderer&) = delete;

  void resize(int width, int height);
  void upload(const LoadedBlock& block);
  // Draws into the offscreen framebuffer; waits for the GPU and returns its time.
  RenderTimes draw(const std::vector<Patch>& patches, const View& view, const WorldFrame& frame,
                   const ShadingSettings& shading);
  // RGBA8, top row first.
  std::vector<uint8_t> read_pixels() const;
  // The drawn triangles, 3 vertices each, world metres relative to view.origin.
  std::vector<float> capture_triangles(const std::vector<Patch>& patches, const View& view,
                                       const WorldFrame& frame, double exaggeration);
  // Copies the image to the window's framebuffer (0).
  void blit_to_default(int width, int height) const;

  size_t triangles_per_patch() const { return static_cast<size_t>(lattice_) * lattice_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  void upload_instances(const std::vector<Patch>& patches, const View& view,
                        const WorldFrame& frame);
  void set_common_uniforms(const GlProgram& p, const View& view, const WorldFrame& frame,
                           double exaggeration) const;

  int size_, lattice_, slots_, width_ = 0, height_ = 0;
  GLsizei index_count_ = 0;
  GlProgram draw_program_, capture_program_;
  GLuint vao_ = 0, lattice_vbo_ = 0, index_buffer_ = 0, instance_buffer_ = 0;
  GLuint heights_ = 0, mask_ = 0;
  GLuint fbo_ = 0, color_ = 0, depth_ = 0;
  GLuint timer_ = 0;
};

}  // namespace globe::viewer
