// Terrain derivatives (see terrain_derivatives.hpp).
#include "analysis/terrain_derivatives.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace globe {
namespace {

constexpr double kA = 6378137.0;          // WGS84 semi-major axis
constexpr double kE2 = 6.69437999014e-3;  // first eccentricity squared
constexpr double kDeg = std::numbers::pi / 180;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

Derivatives derivatives(const Window3& w, double dx, double dy) {
  const double* z = w.z;
  // Horn's weighted differences, x east, y north.
  const double gx = ((z[2] + 2 * z[5] + z[8]) - (z[0] + 2 * z[3] + z[6])) / (8 * dx);
  const double gy = ((z[0] + 2 * z[1] + z[2]) - (z[6] + 2 * z[7] + z[8])) / (8 * dy);
  Derivatives d;
  const double g2 = gx * gx + gy * gy;
  // sqrt, not hypot: gradients of terrain neither overflow nor underflow,
  // and glibc's hypot costs as much as the atan.
  d.slope_deg = std::atan(std::sqrt(g2)) / kDeg;
  if (g2 == 0) {
    d.aspect_deg = d.profile = d.plan = kNaN;
    return d;
  }
  // The slope faces downhill: the direction of -gradient, clockwise from north.
  double a = std::atan2(-gx, -gy) / kDeg;
  if (a < 0) a += 360;
  d.aspect_deg = a >= 360 ? 0 : a;
  // Second derivatives (Zevenbergen & Thorne 1987), y north.
  const double zxx = (z[3] + z[5] - 2 * z[4]) / (dx * dx);
  const double zyy = (z[1] + z[7] - 2 * z[4]) / (dy * dy);
  const double zxy = (z[2] - z[0] - z[8] + z[6]) / (4 * dx * dy);
  // Directional second derivatives along and across the gradient, negated so
  // that convex (crests, ridges) is positive.
  d.profile = -(zxx * gx * gx + 2 * zxy * gx * gy + zyy * gy * gy) / g2;
  d.plan = -(zxx * gy * gy - 2 * zxy * gx * gy + zyy * gx * gx) / g2;
  return d;
}

GroundSpacing ground_spacing(const tileformat::Tiling& tiling, int z, int steps, uint32_t tile_y,
                             int row) {
  const double sp = tiling.sample_spacing(z, steps);
  return ground_spacing_at(tiling, z, steps, tiling.origin_y - (double(tile_y) * steps + row) * sp);
}

GroundSpacing ground_spacing_at(const tileformat::Tiling& tiling, int z, int steps, double y) {
  const double sp = tiling.sample_spacing(z, steps);
  if (tiling.scheme == tileformat::Scheme::kLocal) return {sp, sp};
  double lat = 0, dlat = 0;  // radians; dlat: radians per sample north-south
  if (tiling.scheme == tileformat::Scheme::kGeodetic) {
    lat = y * kDeg;
    dlat = sp * kDeg;
  } else {  // web mercator: y = a ln tan(pi/4 + lat/2), dy/dlat = a / cos(lat)
    lat = 2 * std::atan(std::exp(y / kA)) - std::numbers::pi / 2;
    dlat = sp * std::cos(lat) / kA;
  }
  const double s2 = std::sin(lat) * std::sin(lat);
  const double n = kA / std::sqrt(1 - kE2 * s2);                  // prime vertical radius
  const double m = kA * (1 - kE2) / std::pow(1 - kE2 * s2, 1.5);  // meridional radius
  const double dlon = tiling.scheme == tileformat::Scheme::kGeodetic ? sp * kDeg : sp / kA;
  // At the poles the east-west spacing is 0: keep it tiny but positive.
  return {std::max(n * std::cos(lat) * dlon, 1e-3), m * dlat};
}

}  // namespace globe
