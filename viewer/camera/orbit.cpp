// The window's orbit camera (see orbit.hpp).
#include "camera/orbit.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "camera/ellipsoid.hpp"

namespace globe::viewer {

namespace {

constexpr double kDeg = std::numbers::pi / 180;
constexpr double kMaxPitch = 85.0;

// Rows of enu_rotation: east, north, up at (lat, lon), as ECEF vectors.
struct Enu {
  glm::dvec3 east, north, up;
};
Enu enu_at(double lat, double lon) {
  const glm::dmat3 m = wgs84::enu_rotation(lat, lon);
  // m maps ECEF to ENU; its rows (the columns of the transpose) are the axes.
  const glm::dmat3 t = glm::transpose(m);
  return {t[0], t[1], t[2]};
}

// Heading (degrees) at a point with axes `e` of a view direction f (unit,
// pitch `pitch_deg` there); looking (almost) straight down f says nothing,
// and the horizontal direction `fallback` (ECEF, any length) is used.
double heading_at(const Enu& e, const glm::dvec3& f, double pitch_deg, const glm::dvec3& fallback) {
  const glm::dvec3 d = pitch_deg > 0.5 ? f : fallback;
  return std::atan2(glm::dot(d, e.east), glm::dot(d, e.north)) / kDeg;
}

}  // namespace

Orbit Orbit::from_pose(const CameraPose& p, WorldFrame& w, double ground_m) {
  Orbit o;
  o.target_h_m_ = ground_m;
  const double h = p.heading_deg * kDeg, pi = std::min(p.pitch_deg, kMaxPitch) * kDeg;
  if (!w.globe()) {
    w.set_view_latitude(p.lat);
    const glm::dvec2 crs = w.lonlat_to_crs(p.lon, p.lat);
    const glm::dvec2 eye = w.crs_to_key(crs.x, crs.y);
    o.heading_deg_ = p.heading_deg;
    o.pitch_deg_ = pi / kDeg;
    const double dz = std::max((p.height_m - ground_m) * w.height_scale(), 1.0);
    o.distance_m_ = dz / std::cos(pi);
    const double ground = dz * std::tan(pi);  // horizontal eye-target distance
    o.target_ = eye + glm::dvec2(ground * std::sin(h) / (w.crs_per_key() * w.metres_per_crs_x()),
                                 -ground * std::cos(h) / (w.crs_per_key() * w.metres_per_crs_y()));
    return o;
  }
  // Globe: cast the view ray from the eye onto the sphere through the ground
  // level below it.
  const double lat = p.lat * kDeg, lon = p.lon * kDeg;
  const glm::dvec3 eye = wgs84::to_ecef(lat, lon, p.height_m);
  const Enu e = enu_at(lat, lon);
  const glm::dvec3 f = e.east * (std::sin(h) * std::sin(pi)) +
                       e.north * (std::cos(h) * std::sin(pi)) - e.up * std::cos(pi);
  const double r = glm::length(wgs84::to_ecef(lat, lon, ground_m));
  const double b = glm::dot(eye, f), c = glm::dot(eye, eye) - r * r;
  const double disc = b * b - c;
  double t = disc >= 0 ? -b - std::sqrt(disc) : std::sqrt(std::max(c, 0.0));
  t = std::max(t, 1.0);
  const glm::dvec3 target = eye + t * f;
  const glm::dvec3 llh = wgs84::from_ecef(target);
  o.target_ = {llh.x, llh.y};
  o.target_h_m_ = llh.z;
  o.distance_m_ = t;
  const Enu et = enu_at(llh.x, llh.y);
  const glm::dvec3 back = -f;  // target -> eye
  o.pitch_deg_ = std::acos(std::clamp(glm::dot(back, et.up), -1.0, 1.0)) / kDeg;
  o.pitch_deg_ = std::min(o.pitch_deg_, kMaxPitch);
  o.heading_deg_ = heading_at(et, f, o.pitch_deg_, e.east * std::sin(h) + e.north * std::cos(h));
  return o;
}

CameraPose Orbit::pose(WorldFrame& w, double fov) const {
  const double h = heading_deg_ * kDeg, p = pitch_deg_ * kDeg;
  CameraPose c;
  c.fov_y_deg = fov;
  if (!w.globe()) {
    // The frame's scales are the eye's latitude's (as from_pose took them):
    // found by iterating from the target's.
    const glm::dvec2 tc = w.key_to_crs(target_.x, target_.y);
    w.set_view_latitude(w.crs_to_lonlat(tc.x, tc.y).y);
    const double ground = distance_m_ * std::sin(p), dz = distance_m_ * std::cos(p);
    glm::dvec2 ll{0, 0};
    for (int i = 0; i < 4; ++i) {
      const glm::dvec2 eye =
          target_ - glm::dvec2(ground * std::sin(h) / (w.crs_per_key() * w.metres_per_crs_x()),
                               -ground * std::cos(h) / (w.crs_per_key() * w.metres_per_crs_y()));
      const glm::dvec2 crs = w.key_to_crs(eye.x, eye.y);
      ll = w.crs_to_lonlat(crs.x, crs.y);
      w.set_view_latitude(ll.y);
    }
    c.lon = ll.x, c.lat = ll.y;
    c.height_m = target_h_m_ + dz / w.height_scale();
    c.heading_deg = heading_deg_, c.pitch_deg = pitch_deg_;
    return c;
  }
  const Enu et = enu_at(target_.x, target_.y);
  const glm::dvec3 target = wgs84::to_ecef(target_.x, target_.y, target_h_m_);
  const glm::dvec3 forward = et.east * std::sin(h) + et.north * std::cos(h);
  const glm::dvec3 back = et.up * std::cos(p) - forward * std::sin(p);  // target -> eye
  const glm::dvec3 eye = target + distance_m_ * back;
  const glm::dvec3 llh = wgs84::from_ecef(eye);
  const Enu ee = enu_at(llh.x, llh.y);
  const glm::dvec3 f = -back;
  c.lat = llh.x / kDeg;
  c.lon = std::remainder(llh.y / kDeg, 360.0);
  c.height_m = llh.z;
  c.pitch_deg = std::min(std::acos(std::clamp(-glm::dot(f, ee.up), -1.0, 1.0)) / kDeg, 89.9);
  c.heading_deg = heading_at(ee, f, c.pitch_deg, forward);
  return c;
}

void Orbit::turn(double d_heading_deg, double d_pitch_deg) {
  heading_deg_ = std::fmod(heading_deg_ + d_heading_deg + 360, 360);
  pitch_deg_ = std::clamp(pitch_deg_ + d_pitch_deg, 0.0, kMaxPitch);
}

void Orbit::pan(double dx_px, double dy_px, double px_per_rad, WorldFrame& w) {
  const double m = distance_m_ / px_per_rad;  // metres per pixel at the target
  const double h = heading_deg_ * kDeg;
  const double east = -dx_px * m * std::cos(h) - dy_px * m * std::sin(h);
  const double north = dx_px * m * std::sin(h) - dy_px * m * std::cos(h);
  if (!w.globe()) {
    target_ += glm::dvec2(east / (w.crs_per_key() * w.metres_per_crs_x()),
                          -north / (w.crs_per_key() * w.metres_per_crs_y()));
    return;
  }
  const double n = wgs84::prime_vertical_radius(target_.x), s = std::sin(target_.x);
  const double m_radius = n * (1 - wgs84::kE2) / (1 - wgs84::kE2 * s * s);  // meridian
  target_.x = std::clamp(target_.x + north / m_radius, -std::numbers::pi / 2, std::numbers::pi / 2);
  target_.y += east / (n * std::max(std::cos(target_.x), 1e-6));
}

void Orbit::zoom(double factor, WorldFrame& w, const View* view, const glm::dvec3* towards) {
  distance_m_ = std::clamp(distance_m_ * factor, 1.0, 1e8);
  if (!view || !towards || factor >= 1) return;
  const glm::dvec3 k = w.world_to_key_height(*towards, view->origin);
  glm::dvec2 to;
  if (!w.globe()) {
    to = {k.x, k.y};
  } else {
    const glm::dvec2 ll = w.key_to_latlon(k.x, k.y);
    to = ll;
    to.y = target_.y + std::remainder(to.y - target_.y, 2 * std::numbers::pi);
  }
  // The point under the cursor keeps (about) its place on screen.
  target_ += (to - target_) * (1 - factor);
}

}  // namespace globe::viewer
