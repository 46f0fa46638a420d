// One layer the scene draws over the terrain (imagery, lines, charts): the
// interface TerrainScene holds its layers by. The scene draws them in order,
// each over the image so far (the terrain's colour at first, then the layer
// before's output), and splits the tile budget by their shares; the window
// and headless runs ask them for picks, style reloads and statistics
// without knowing their kind (docs/architecture.md, "A new viewer layer").
#pragma once

#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "camera/camera.hpp"
#include "camera/world_frame.hpp"
#include "render/line_renderer.hpp"
#include "render/terrain_renderer.hpp"

namespace globe::viewer {

// Whether a frame waits for the tiles it needs: kSettle keeps selecting and
// loading until nothing the view needs is missing (headless snapshots);
// kAsReady never waits for I/O (interactive windows).
enum class Loading { kSettle, kAsReady };

// What one layer's pass draws over.
struct LayerPass {
  GBuffer g;             // the terrain's G-buffer; g.color: the image so far, as a texture
  GLuint below_fbo = 0;  // the image so far, as a framebuffer (its colour is g.color)
  const View& view;
  const WorldFrame& world;
  const TerrainRenderer& terrain;       // its frame uniforms (lifted lines, chart depth)
  const TerrainHeights& heights;        // the resident blocks' heights on the GPU
  const ShadingSettings& shading;       // exaggeration, sun, lens
  double height_lo = 0, height_hi = 0;  // the terrain's data range of heights (m)
  bool imagery_unlit = false;           // --shading imagery
  Loading loading = Loading::kSettle;
};

class SceneLayer {
 public:
  virtual ~SceneLayer() = default;
  virtual void resize(int width, int height) = 0;
  // The layer's pass over pass.g / pass.below_fbo into output_fbo(); returns
  // its GPU time in ms.
  virtual double draw(const LayerPass& pass) = 0;
  virtual GLuint output_fbo() const = 0;
  virtual GLuint output_texture() const = 0;  // output_fbo()'s colour
  // Whether tiles are still being read (the window keeps drawing).
  virtual bool loading() = 0;
  // Tiles the last frame wanted and has not got yet (the window's title).
  virtual size_t waiting() const { return 0; }
  // Re-reads the layer's style file (always, or if it changed); true when the
  // look changed. Layers without a style file: false.
  virtual bool reload_style(bool always) {
    (void)always;
    return false;
  }
  // Whether pick() says what lies under a pixel.
  virtual bool picks() const { return false; }
  // What lies at pixel (x, y) (from the top-left) in the last frame, "" where
  // nothing does. highlight: the frames that follow show it (lines).
  virtual std::string pick(int x, int y, bool highlight) {
    (void)x, (void)y, (void)highlight;
    return "";
  }
  // --pick-format json: the member this layer's pick fills ("area", "line",
  // "chart"; "" for none) and the topmost feature at pixel (x, y) as a JSON
  // object with its "id" and attributes ("null" for none).
  virtual const char* pick_kind() const { return ""; }
  virtual std::string pick_json(int x, int y) {
    (void)x, (void)y;
    return "null";
  }
  // Whether a pick made the next frame look different (a highlight).
  virtual bool picked_highlight() const { return false; }
  // Screen rectangles (x0, y0, x1, y1 from the top-left) the last frame's
  // overlays (legends) cover, which labels keep clear of.
  virtual std::vector<glm::vec4> overlay_boxes() const { return {}; }
  // This layer's members of `--stats`' JSON object, each starting ", "
  // (docs/viewer.md "--stats"); ms: the median of its passes.
  virtual std::string stats_json(double ms) const = 0;
};

}  // namespace globe::viewer
