// Heatmap instances (see heat_samples.hpp).
#include "app/heat_samples.hpp"

#include <cmath>

#include <algorithm>

#include <glm/geometric.hpp>

#include "app/color_relief_file.hpp"
#include "render/color_ramp.hpp"

namespace globe::viewer {

HeatmapStyle heatmap_style(double opacity, const std::optional<std::string>& colormap) {
  HeatmapStyle hs;
  hs.opacity = static_cast<float>(opacity);
  if (!colormap) return hs;
  const RampTable t = tabulate(read_color_relief_file(*colormap).ramp, 0, 100);
  hs.ramp.resize(256 * 4);
  for (int i = 0; i < 256; ++i) {  // the table spans its stops; the heatmap spans 0..100 %
    const Rgba c = t.at(100.0 * i / 255);
    std::copy(c.begin(), c.end(), hs.ramp.begin() + i * 4);
  }
  return hs;
}

HeatFrame::HeatFrame(const View& view, const WorldFrame& world) : view_(view), world_(world) {
  origin_crs_ = world.key_to_crs(double(view.origin.x), double(view.origin.y));
  gx_ = world.ground_per_crs_x(), gy_ = world.ground_per_crs_y();
  ground_per_m_ = world.ground_height_scale();  // ground units per metre at the view latitude
  const tileformat::Tiling& t = world.tiling();
  span_ = t.wraps_x() ? t.roots_x * t.root_size : 0;  // CRS units around the Earth
}

double HeatFrame::radius_m(glm::dvec2 key, HeatRadius radius) const {
  if (radius.metres) return radius.value;
  // Pixels: the metres across that many at the sample.
  return radius.value *
         glm::length(world_.key_to_world(key.x, key.y, 0, view_.origin) - view_.eye) /
         view_.pixels_per_radian / ground_per_m_;
}

ChartInstance HeatFrame::instance(glm::dvec2 key, double weight, HeatRadius radius) const {
  const glm::dvec2 crs = world_.key_to_crs(key.x, key.y);
  double dx = crs.x - origin_crs_.x;
  if (span_ > 0) dx -= span_ * std::round(dx / span_);  // the copy nearest the view
  ChartInstance c{};
  c.key[0] = static_cast<int32_t>(std::floor(key.x));
  c.key[1] = static_cast<int32_t>(std::floor(key.y));
  c.frac[0] = static_cast<float>(key.x - std::floor(key.x));
  c.frac[1] = static_cast<float>(key.y - std::floor(key.y));
  c.params[0] = static_cast<float>(dx * gx_);
  c.params[1] = static_cast<float>((crs.y - origin_crs_.y) * gy_);
  c.params[2] = static_cast<float>(weight);
  c.params[3] = static_cast<float>(radius_m(key, radius) * ground_per_m_);
  return c;
}

}  // namespace globe::viewer
