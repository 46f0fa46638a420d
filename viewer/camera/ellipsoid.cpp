// WGS84 ellipsoid (see ellipsoid.hpp).
#include "camera/ellipsoid.hpp"

#include <cmath>

namespace globe::viewer::wgs84 {

double prime_vertical_radius(double lat) {
  const double s = std::sin(lat);
  return kA / std::sqrt(1 - kE2 * s * s);
}

glm::dvec3 to_ecef(double lat, double lon, double h) {
  const double n = prime_vertical_radius(lat);
  const double c = std::cos(lat);
  return {(n + h) * c * std::cos(lon), (n + h) * c * std::sin(lon),
          (n * (1 - kE2) + h) * std::sin(lat)};
}

glm::dvec3 from_ecef(const glm::dvec3& p) {
  const double lon = std::atan2(p.y, p.x);
  const double r = std::hypot(p.x, p.y);
  // Fixed-point iteration on latitude; converges to 1e-12 rad in a few steps
  // for any point outside a small ball around the centre.
  double lat = std::atan2(p.z, r * (1 - kE2));
  double h = 0;
  for (int i = 0; i < 10; ++i) {
    const double n = prime_vertical_radius(lat);
    const double c = std::cos(lat), s = std::sin(lat);
    h = std::abs(c) > 1e-9 ? r / c - n : std::abs(p.z) / std::abs(s) - n * (1 - kE2);
    const double next = std::atan2(p.z, r * (1 - kE2 * n / (n + h)));
    const bool done = std::abs(next - lat) < 1e-13;
    lat = next;
    if (done) break;
  }
  const double n = prime_vertical_radius(lat);
  const double c = std::cos(lat), s = std::sin(lat);
  h = std::abs(c) > 0.5 ? r / c - n : p.z / s - n * (1 - kE2);
  return {lat, lon, h};
}

glm::dmat3 enu_rotation(double lat, double lon) {
  const double sl = std::sin(lat), cl = std::cos(lat), so = std::sin(lon), co = std::cos(lon);
  // glm is column-major: m[c][r]. Rows are east, north, up.
  glm::dmat3 m;
  m[0] = {-so, -sl * co, cl * co};
  m[1] = {co, -sl * so, cl * so};
  m[2] = {0, cl, sl};
  return m;
}

}  // namespace globe::viewer::wgs84
