// The heatmap's instances (docs/viewer.md "Heatmaps"): a place or a sample
// of a line as ChartInstance for ChartRenderer::draw_heatmap — its anchor in
// key units, its ground point relative to the view origin (the G-buffer's
// ground frame), its weight and its kernel radius in ground units. Shared by
// the heatmaps of point packages (ChartLayer) and of line packages
// (LineLayer).
#pragma once

#include <optional>
#include <string>

#include <glm/vec2.hpp>

#include "camera/camera.hpp"
#include "camera/world_frame.hpp"
#include "render/chart_renderer.hpp"

namespace globe::viewer {

// The heatmap's look from the settings: opacity and, with
// --heatmap-colormap, the colour file's ramp over 0..100 % of the largest
// density (UsageError naming the file when it cannot be read).
HeatmapStyle heatmap_style(double opacity, const std::optional<std::string>& colormap);

struct HeatRadius {
  double value = 30;
  bool metres = false;  // else screen pixels at each sample
};

class HeatFrame {
 public:
  HeatFrame(const View& view, const WorldFrame& world);
  // The instance of a sample at key point `key` weighing `weight`.
  ChartInstance instance(glm::dvec2 key, double weight, HeatRadius radius) const;
  // Ground units per metre at the view latitude (density per m^2 = per
  // ground unit^2 x this squared).
  double ground_per_m() const { return ground_per_m_; }
  // The kernel radius in metres at key point `key`.
  double radius_m(glm::dvec2 key, HeatRadius radius) const;

 private:
  const View& view_;
  const WorldFrame& world_;
  glm::dvec2 origin_crs_{0};
  double gx_ = 1, gy_ = 1, ground_per_m_ = 1, span_ = 0;
};

}  // namespace globe::viewer
