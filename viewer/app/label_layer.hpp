// The labels of one view (docs/viewer.md "Labels"), drawn last, over
// everything: the names the vector packages store (label_set.hpp), placed
// per frame - projected onto the terrain as drawn, sized by distance with a
// legibility cutoff, tested against the terrain's depth in the G-buffer at
// several points of each label (never drawn through a ridge), kept apart by
// the collision grid with hysteresis (label_placement.hpp) - and drawn as
// SDF glyphs with a halo. Point labels sit beside their place, area labels
// on their pole of inaccessibility, line labels follow the line's curve.
// The last frame's labels are what --labels-json writes.
#pragma once

#include <array>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "app/chart_layer.hpp"
#include "app/label_placement.hpp"
#include "app/label_settings.hpp"
#include "app/scene_layer.hpp"
#include "data/label_set.hpp"
#include "render/label_renderer.hpp"

namespace globe::viewer {

class LabelLayer final : public SceneLayer {
 public:
  // `packages`: the view's vector packages. Has labels() false when none of
  // them stores labels.
  LabelLayer(const std::vector<std::string>& packages, const LabelSettings& settings,
             const WorldFrame& world, int width, int height);
  ~LabelLayer() override;
  bool has_labels() const { return !set_.labels().empty(); }

  void resize(int width, int height) override;
  double draw(const LayerPass& pass) override;
  GLuint output_fbo() const override { return renderer_.output_fbo(); }
  GLuint output_texture() const override { return renderer_.output_texture(); }
  bool loading() override { return false; }
  std::string stats_json(double ms) const override;
  // The window's N key.
  void toggle() {
    settings_.enabled = !settings_.enabled;
    placer_.reset();
  }
  bool enabled() const { return settings_.enabled; }
  // The chart layer whose charts labels keep clear of (nullptr: none).
  void set_charts(const ChartLayer* charts) { charts_ = charts; }
  // The layers drawn before, whose legends labels keep clear of.
  void set_layers_below(std::vector<const SceneLayer*> layers) { below_ = std::move(layers); }
  // The last frame's placed labels as one JSON object (docs/viewer.md
  // "--labels-json"): candidates in view, shown, and per label its text,
  // source, anchor, box, alpha and (line labels) glyphs.
  std::string frame_json() const;

 private:
  struct Placed {
    uint32_t label;
    ScreenBox box;
    float alpha;
    std::vector<std::array<float, 3>> glyphs;  // line labels: x, y, angle (degrees)
  };
  void build_probes(const WorldFrame& world);

  LabelSettings settings_;
  const ChartLayer* charts_ = nullptr;
  std::vector<const SceneLayer*> below_;
  LabelSet set_;
  LabelRenderer renderer_;
  LabelPlacer placer_;
  std::vector<uint32_t> anchor_probe_;   // per label
  std::vector<glm::vec3> anchor_up_;     // per label: the ground's up at its anchor (ECEF)
  std::vector<LabelProbe> path_points_;  // every line label's path, projected while in view
  std::vector<glm::vec3> path_up_;       // per path point: the ground's up there (ECEF)
  std::vector<std::pair<uint32_t, uint32_t>> path_probes_;  // per label: first path point, count
  std::vector<Placed> placed_;
  size_t candidates_ = 0, occluded_ = 0, illegible_ = 0;
  double place_ms_ = 0;  // CPU: layout, collision, glyphs
  double probe_ms_ = 0;  // the GPU passes with their read-backs
  int width_ = 0, height_ = 0;
  bool first_frame_ = true;
  glm::dmat4 last_view_{0.0};
  std::chrono::steady_clock::time_point last_time_;
  std::vector<uint64_t> last_placed_keys_;  // drawn last frame (occlusion hysteresis)
  bool first_upload_ = true;
};

}  // namespace globe::viewer
