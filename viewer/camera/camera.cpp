// Camera poses and views (see camera.hpp).
#include "camera/camera.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "camera/ellipsoid.hpp"

namespace globe::viewer {

namespace {
constexpr double kDeg = std::numbers::pi / 180;
}

CameraPose CameraPose::parse(const std::string& text) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    try {
      size_t used = 0;
      v.push_back(std::stod(item, &used));
      if (used != item.size()) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw std::invalid_argument("'" + item + "' is not a number");
    }
  }
  if (v.size() != 5)
    throw std::invalid_argument("expected lon,lat,height_m,heading_deg,pitch_deg (5 numbers)");
  CameraPose p;
  p.lon = v[0], p.lat = v[1], p.height_m = v[2], p.heading_deg = v[3], p.pitch_deg = v[4];
  if (p.lat < -90 || p.lat > 90 || p.lon < -540 || p.lon > 540)
    throw std::invalid_argument("longitude/latitude out of range");
  if (p.pitch_deg < 0 || p.pitch_deg > 89.9)
    throw std::invalid_argument("pitch must be in 0..89.9 degrees (0 looks straight down)");
  return p;
}

std::string CameraPose::str() const {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%.7f,%.7f,%.2f,%.2f,%.2f", lon, lat, height_m, heading_deg,
                pitch_deg);
  return buf;
}

View make_view(const CameraPose& pose, WorldFrame& frame, int width, int height, double z_top_world,
               double z_bottom_world) {
  frame.set_view_latitude(pose.lat);
  const glm::dvec2 crs = frame.lonlat_to_crs(pose.lon, pose.lat);
  const glm::dvec2 key = frame.crs_to_key(crs.x, crs.y);
  View v;
  v.origin = {static_cast<int64_t>(std::llround(key.x)), static_cast<int64_t>(std::llround(key.y))};
  v.width = width;
  v.height = height;
  v.eye = frame.key_to_world(key.x, key.y, pose.height_m, v.origin);
  const double h = pose.heading_deg * kDeg, p = pose.pitch_deg * kDeg;
  const glm::dvec3 forward{std::sin(h) * std::sin(p), std::cos(h) * std::sin(p), -std::cos(p)};
  const glm::dvec3 up{std::sin(h) * std::cos(p), std::cos(h) * std::cos(p), std::sin(p)};
  v.view = glm::lookAt(v.eye, v.eye + forward, up);
  const double fovy = pose.fov_y_deg * kDeg;
  v.pixels_per_radian = height / (2 * std::tan(fovy / 2));
  // Near plane: half the height above the highest terrain (at least 1 m);
  // far plane: far enough to see the horizon of a 20,000 km wide map.
  const double above = v.eye.z - z_top_world;
  v.near_m = std::max(1.0, above * 0.5 * std::cos(std::min(p, 1.3)));
  if (frame.globe()) {
    // Far enough for the horizon, and for peaks standing behind it.
    auto horizon = [](double h) {
      return std::sqrt(std::max(h, 0.0) * (2 * wgs84::kA + std::max(h, 0.0)));
    };
    v.far_m = std::max(horizon(pose.height_m) + horizon(z_top_world) + 1000, v.near_m * 10);
  } else {
    const double depth = std::max(v.eye.z - z_bottom_world, 1.0);
    // At most 40,000 km, or twice the eye's depth above the lowest ground:
    // the whole web mercator square, framed from above, lies 50,000 km down.
    v.far_m = std::clamp(depth / std::max(std::cos(p + fovy / 2), 0.02), v.near_m * 10,
                         std::max(4e7, 2 * depth));
  }
  v.proj = glm::perspective(fovy, double(width) / height, v.near_m, v.far_m);
  const glm::dmat4 vp = v.proj * v.view;
  v.view_proj = glm::mat4(vp);
  // Gribb-Hartmann plane extraction from the rows of view-projection.
  const glm::dmat4 t = glm::transpose(vp);
  v.planes = {t[3] + t[0], t[3] - t[0], t[3] + t[1], t[3] - t[1], t[3] + t[2], t[3] - t[2]};
  for (auto& pl : v.planes)
    pl /= glm::length(glm::dvec3(pl));
  return v;
}

CameraPose fit_pose(const tileformat::Bounds& b, WorldFrame& frame, int width, int height,
                    double z_top_m) {
  CameraPose pose;
  const glm::dvec2 centre = frame.crs_to_lonlat((b.min_x + b.max_x) / 2, (b.min_y + b.max_y) / 2);
  pose.lon = centre.x;
  pose.lat = centre.y;
  frame.set_view_latitude(pose.lat);
  if (frame.globe()) {
    const tileformat::Bounds ll{
        frame.crs_to_lonlat(b.min_x, b.min_y).x, frame.crs_to_lonlat(b.min_x, b.min_y).y,
        frame.crs_to_lonlat(b.max_x, b.max_y).x, frame.crs_to_lonlat(b.max_x, b.max_y).y};
    if (ll.width() > 90 || ll.height() > 60) {
      // The whole disc: the ellipsoid's equatorial radius fills the view's
      // height (or width, if narrower), with 5% to spare.
      const double half = std::min(pose.fov_y_deg * kDeg / 2,
                                   std::atan(std::tan(pose.fov_y_deg * kDeg / 2) * width / height));
      pose.height_m = wgs84::kA * 1.05 / std::sin(half) - wgs84::kA;
      return pose;
    }
    // A smaller area: metres at its own latitude.
    const double c = std::cos(pose.lat * kDeg);
    const double per_crs = frame.tiling().scheme == tileformat::Scheme::kWebMercator
                               ? c
                               : wgs84::kA * std::numbers::pi / 180;
    const double w_m =
        b.width() * per_crs * (frame.tiling().scheme == tileformat::Scheme::kWebMercator ? 1 : c);
    const double h_m = b.height() * per_crs;
    const double half = std::max(w_m / (double(width) / height), h_m) / 2 * 1.05;
    pose.height_m = z_top_m + half / std::tan(pose.fov_y_deg * kDeg / 2);
    return pose;
  }
  const double w_m = b.width() * frame.metres_per_crs_x();
  const double h_m = b.height() * frame.metres_per_crs_y();
  const double aspect = double(width) / height;
  const double half = std::max(w_m / aspect, h_m) / 2 * 1.05;
  const double dist = half / std::tan(pose.fov_y_deg * kDeg / 2);
  pose.height_m = z_top_m + dist / frame.height_scale();
  return pose;
}

}  // namespace globe::viewer
