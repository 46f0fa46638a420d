// What one viewer session shows: the opened terrain package, its block cache,
// the patch selector, the world frame and the renderer, the optional image,
// line and chart layers, and the per-frame sequence (select -> request ->
// upload -> draw terrain -> imagery -> line pass -> chart pass) that both the
// window and the headless runs use.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "app/area_layer.hpp"
#include "app/chart_layer.hpp"
#include "app/data_ranges.hpp"
#include "app/edge_scale.hpp"
#include "app/elevation_ramp.hpp"
#include "app/flat_base.hpp"
#include "app/image_layers.hpp"
#include "app/label_layer.hpp"
#include "app/line_layer.hpp"
#include "app/relief_scale.hpp"
#include "app/scene_layer.hpp"
#include "app/viewer_settings.hpp"
#include "camera/camera.hpp"
#include "camera/world_frame.hpp"
#include "data/block_cache.hpp"
#include "data/ground_probe.hpp"
#include "render/patch_selection.hpp"
#include "render/polar_caps.hpp"
#include "render/readback.hpp"
#include "render/terrain_renderer.hpp"

namespace globe::viewer {

struct FrameResult {
  CameraPose pose;  // the pose drawn: the one asked for, raised above the ground if below it
  View view;
  std::vector<Patch> patches;
  SelectionStats selection;
  double select_ms = 0, terrain_ms = 0;
  std::vector<double> layer_ms;  // GPU ms of each layer's pass, in the order of layers()
};

class TerrainScene {
 public:
  // Opens and checks the packages (throws InputError naming the file). An
  // OpenGL context must be current (the renderer is created here).
  explicit TerrainScene(const ViewerSettings& settings);
  ~TerrainScene();

  // Loads the root blocks (needed for heights and --fit) and returns the pose
  // to start from: --camera, else a view of the whole package.
  CameraPose initial_pose();
  void resize(int width, int height);

  enum class Output { kDraw, kSelectOnly };
  // One frame (Loading: whether it waits for what the view needs);
  // kSelectOnly stops after the patch selection. A pose below the ground
  // under it (times the exaggeration) is raised above it, with a note on
  // stderr when that starts (docs/viewer.md "Camera").
  FrameResult frame(const CameraPose& pose, Loading loading, Output output);
  std::vector<CapturedVertex> capture(const FrameResult& f) {
    return renderer_->capture_triangles(f.patches, f.view, *world_, settings_.shading.exaggeration);
  }

  TerrainRenderer& renderer() { return *renderer_; }
  // The layers over the terrain, in drawing order (imagery, lines, charts).
  const std::vector<std::unique_ptr<SceneLayer>>& layers() const { return layers_; }
  // The topmost layer that picks (nullptr: none).
  SceneLayer* picking_layer();
  // The layers by kind, for the window's keys that act on one (nullptr: none).
  LineLayer* lines() { return lines_; }
  AreaLayer* areas() { return areas_; }
  ChartLayer* charts() { return charts_; }
  LabelLayer* labels() { return labels_; }  // nullptr: no package stores labels
  ImageLayers* images() { return images_; }
  // The finished image (terrain, imagery and lines): framebuffer and pixels.
  GLuint output_fbo() const;
  std::vector<uint8_t> read_pixels() const;
  // Whether any layer is still reading tiles (the window keeps drawing).
  bool loading();
  // The fraction of the last frame's pixels that show terrain.
  double ground_fraction() const {
    return viewer::ground_fraction(renderer_->gbuffer().fbo, renderer_->width(),
                                   renderer_->height());
  }
  BlockCache& cache() { return *cache_; }
  WorldFrame& world() { return *world_; }
  // The ground under pixel (x, y) (from the top-left) of the last frame drawn
  // with `view`: longitude, latitude (degrees) and height (metres, before
  // exaggeration); nullopt where the pixel shows no ground.
  std::optional<glm::dvec3> ground_at(const View& view, int x, int y) const;
  const TerrainPackage& package() const { return cache_->package(); }
  ViewerSettings& settings() { return settings_; }
  double top_height_m() { return selector_->top_height_m(*cache_); }
  // The colour ramp; after an edit, apply_ramp() hands the table for the
  // current shading mode to the renderer.
  ElevationRamp& ramp() { return *ramp_; }
  const DataRanges& data_ranges() const { return ranges_; }
  void apply_ramp() {
    ramp_mode_ = settings_.shading.mode;
    renderer_->set_ramp(ramp_->table(ramp_mode_, flow_largest_));
  }
  // "" when `shading` can be drawn (its analysis layers are there), else why not.
  std::string shading_problem(const ShadingSettings& shading) const;

 private:
  TerrainHeights terrain_heights(const View& view);  // for the layers' passes
  // The terrain renderer, told the data's ranges and the analysis layers it
  // shades with, and the polar caps on the globe.
  void make_renderer(const std::string& path, const std::optional<std::string>& analysis);
  void upload_loaded();
  void load_now(const std::vector<tileformat::TileId>& tiles);  // waits for them
  void sample_heights();  // fixes the elevation ramp's data range
  View make(const CameraPose& pose);
  CameraPose above_ground(const CameraPose& pose);
  void find_neighbours(std::vector<Patch>& patches);  // Patch::neighbours from the cache
  // Ground metres between a block's samples east and south (at its centre).
  std::pair<double, double> block_spacing_m(tileformat::TileId id) const;

  ViewerSettings settings_;
  std::unique_ptr<FlatBase> base_;  // the ground when no terrain is given (outlives its readers)
  std::unique_ptr<BlockCache> cache_;
  std::unique_ptr<PatchSelector> selector_;
  std::unique_ptr<WorldFrame> world_;
  std::unique_ptr<TerrainRenderer> renderer_;
  std::unique_ptr<PolarCaps> caps_;
  std::vector<std::unique_ptr<SceneLayer>> layers_;  // drawn in this order
  ImageLayers* images_ = nullptr;                    // those of layers_ by kind
  LineLayer* lines_ = nullptr;
  AreaLayer* areas_ = nullptr;
  ChartLayer* charts_ = nullptr;
  LabelLayer* labels_ = nullptr;
  std::unique_ptr<ElevationRamp> ramp_;
  std::unique_ptr<GroundProbe> ground_;
  bool raised_ = false;                       // the last frame's pose was raised above the ground
  ReliefScale relief_;                        // the hillshade's relief stretch per zoom
  bool auto_relief_ = true;                   // off when --exaggeration is given
  EdgeScale edges_;                           // the edges shading's stretch per zoom
  DataRanges ranges_;                         // the slope and sky-view ramps on this data
  std::optional<std::string> analysis_path_;  // the analysis package, if any
  std::vector<tileformat::AnalysisLayer> analysis_layers_;  // and its layers
  float flow_largest_ = kNoFlow;                            // log2 m^2: the flow shading's top
  Shading ramp_mode_ = Shading::kElevation;                 // the mode the ramp was tabulated for
  int ramp_zoom_ = -1;  // zoom whose blocks feed the ramp's samples (-1: done)
  std::vector<tileformat::TileId> ramp_level_;  // its blocks loaded so far
};

}  // namespace globe::viewer
