// Coordinate systems of the viewer (see world_frame.hpp).
#include "camera/world_frame.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "camera/proj_crs.hpp"

namespace globe::viewer {

namespace {
constexpr double kMetresPerDegreeLat = 110574.0;
constexpr double kMetresPerDegreeLonEquator = 111320.0;
}  // namespace

WorldFrame::WorldFrame(const tileformat::Tiling& tiling, int steps, int key_zoom)
    : tiling_(tiling),
      steps_(steps),
      key_zoom_(key_zoom),
      crs_per_key_(tiling.sample_spacing(key_zoom, steps)) {
  geographic_ = crs_is_geographic(tiling.crs, "package CRS");
  to_crs_ = std::make_unique<ProjTransform>("EPSG:4326", tiling.crs, "package CRS");
  to_lonlat_ = std::make_unique<ProjTransform>(tiling.crs, "EPSG:4326", "package CRS");
  set_view_latitude(0);
}

WorldFrame::~WorldFrame() = default;

void WorldFrame::set_view_latitude(double lat_deg) {
  const double c = std::cos(std::clamp(lat_deg, -85.0, 85.0) * std::numbers::pi / 180);
  if (tiling_.scheme == tileformat::Scheme::kWebMercator) {
    mx_ = my_ = 1;
    hz_ = 1 / c;  // Mercator metres are stretched by 1/cos(lat); heights follow
  } else if (geographic_) {
    mx_ = kMetresPerDegreeLonEquator * c;
    my_ = kMetresPerDegreeLat;
    hz_ = 1;
  } else {
    mx_ = my_ = hz_ = 1;
  }
}

glm::dvec2 WorldFrame::key_to_crs(double kx, double ky) const {
  return {tiling_.origin_x + kx * crs_per_key_, tiling_.origin_y - ky * crs_per_key_};
}

glm::dvec2 WorldFrame::crs_to_key(double cx, double cy) const {
  return {(cx - tiling_.origin_x) / crs_per_key_, (tiling_.origin_y - cy) / crs_per_key_};
}

glm::dvec2 WorldFrame::lonlat_to_crs(double lon, double lat) const {
  double x = lon, y = lat;
  if (!to_crs_->transform(x, y))
    throw std::runtime_error("cannot project lon/lat " + std::to_string(lon) + "," +
                             std::to_string(lat) + " to the package CRS");
  return {x, y};
}

glm::dvec2 WorldFrame::crs_to_lonlat(double x, double y) const {
  if (!to_lonlat_->transform(x, y)) throw std::runtime_error("cannot convert CRS point to lon/lat");
  return {x, y};
}

}  // namespace globe::viewer
