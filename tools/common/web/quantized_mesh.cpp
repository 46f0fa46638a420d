// quantized-mesh-1.0 tiles (see quantized_mesh.hpp).
#include "web/quantized_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace globe::web {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kA = 6378137.0;             // WGS84 semi-major axis
constexpr double kB = 6356752.3142451793;    // semi-minor axis
constexpr double kE2 = 6.69437999014132e-3;  // first eccentricity squared
constexpr uint32_t kMax16BitVertices = 64 * 1024;

class Writer {
 public:
  std::vector<uint8_t> bytes;
  void u8(uint8_t v) { bytes.push_back(v); }
  void u16(uint16_t v) { put(v, 2); }
  void u32(uint32_t v) { put(v, 4); }
  void f32(float v) {
    uint32_t bits;
    std::memcpy(&bits, &v, 4);
    put(bits, 4);
  }
  void f64(double v) {
    uint64_t bits;
    std::memcpy(&bits, &v, 8);
    put(bits, 8);
  }
  void vec3(const Vec3& v) {
    for (double c : v)
      f64(c);
  }
  void index(uint32_t v, bool wide) { wide ? u32(v) : u16(static_cast<uint16_t>(v)); }

 private:
  void put(uint64_t v, int n) {
    for (int i = 0; i < n; ++i)
      bytes.push_back(static_cast<uint8_t>(v >> (8 * i)));
  }
};

uint16_t zig_zag(int32_t v) {
  return static_cast<uint16_t>((v << 1) ^ (v >> 31));
}

double norm(const Vec3& v) {
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

}  // namespace

std::vector<uint8_t> encode_quantized_mesh(const QuantizedMeshTile& t) {
  const uint32_t n = static_cast<uint32_t>(t.u.size());
  const bool wide = n > kMax16BitVertices;
  Writer w;
  // QuantizedMeshHeader.
  w.vec3(t.center);
  w.f32(t.min_height);
  w.f32(t.max_height);
  w.vec3(t.sphere_center);
  w.f64(t.sphere_radius);
  w.vec3(t.horizon_point);
  // VertexData: u, v, height as zig-zag deltas.
  w.u32(n);
  for (const std::vector<uint16_t>* a : {&t.u, &t.v, &t.height}) {
    int32_t previous = 0;
    for (uint16_t value : *a) {
      w.u16(zig_zag(int32_t(value) - previous));
      previous = value;
    }
  }
  // IndexData, aligned to its index size; high-water-mark coded.
  while (w.bytes.size() % (wide ? 4 : 2))
    w.u8(0);
  w.u32(static_cast<uint32_t>(t.triangles.size() / 3));
  uint32_t highest = 0;
  for (uint32_t index : t.triangles) {
    if (index > highest)
      throw std::invalid_argument("quantized-mesh: vertices not numbered in order of first use");
    w.index(highest - index, wide);
    if (index == highest) ++highest;
  }
  // EdgeIndices: west, south, east, north.
  for (const std::vector<uint32_t>* edge : {&t.west, &t.south, &t.east, &t.north}) {
    w.u32(static_cast<uint32_t>(edge->size()));
    for (uint32_t index : *edge)
      w.index(index, wide);
  }
  // Extensions: 1 oct-encoded vertex normals, 2 water mask.
  if (!t.oct_normals.empty()) {
    w.u8(1);
    w.u32(static_cast<uint32_t>(t.oct_normals.size()));
    w.bytes.insert(w.bytes.end(), t.oct_normals.begin(), t.oct_normals.end());
  }
  if (!t.water_mask.empty()) {
    w.u8(2);
    w.u32(static_cast<uint32_t>(t.water_mask.size()));
    w.bytes.insert(w.bytes.end(), t.water_mask.begin(), t.water_mask.end());
  }
  return std::move(w.bytes);
}

EcefLongitude ecef_longitude(double lon_deg) {
  const double lon = lon_deg * kPi / 180;
  return {std::cos(lon), std::sin(lon)};
}

EcefLatitude ecef_latitude(double lat_deg) {
  const double lat = lat_deg * kPi / 180;
  const double s = std::sin(lat), c = std::cos(lat);
  return {c, s, kA / std::sqrt(1 - kE2 * s * s)};
}

Vec3 ecef(const EcefLongitude& lon, const EcefLatitude& lat, double height_m) {
  return {(lat.n + height_m) * lat.c * lon.c, (lat.n + height_m) * lat.c * lon.s,
          (lat.n * (1 - kE2) + height_m) * lat.s};
}

Vec3 ecef(double lon_deg, double lat_deg, double height_m) {
  return ecef(ecef_longitude(lon_deg), ecef_latitude(lat_deg), height_m);
}

Vec3 ellipsoid_normal(double lon_deg, double lat_deg) {
  const double lon = lon_deg * kPi / 180, lat = lat_deg * kPi / 180;
  return {std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat)};
}

std::array<uint8_t, 2> oct_encode(const Vec3& v) {
  const double l1 = std::fabs(v[0]) + std::fabs(v[1]) + std::fabs(v[2]);
  double x = v[0] / l1, y = v[1] / l1;
  if (v[2] < 0) {
    const double ox = x;
    x = (1 - std::fabs(y)) * (ox >= 0 ? 1 : -1);
    y = (1 - std::fabs(ox)) * (y >= 0 ? 1 : -1);
  }
  auto snorm = [](double c) {
    return static_cast<uint8_t>(std::lround((std::clamp(c, -1.0, 1.0) * 0.5 + 0.5) * 255));
  };
  return {snorm(x), snorm(y)};
}

// EllipsoidalOccluder.computeHorizonCullingPoint: in the space where the
// ellipsoid is the unit sphere, the point along the direction far enough out
// that the cone of its horizon hides each position.
std::optional<Vec3> horizon_occlusion_point(const std::vector<Vec3>& positions,
                                            const Vec3& direction) {
  auto scaled = [](const Vec3& p) { return Vec3{p[0] / kA, p[1] / kA, p[2] / kB}; };
  Vec3 d = scaled(direction);
  const double dn = norm(d);
  if (dn == 0) return std::nullopt;
  for (double& c : d)
    c /= dn;
  double magnitude = 0;
  for (const Vec3& position : positions) {
    const Vec3 p = scaled(position);
    const double m2 = std::max(1.0, p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    const double m = std::sqrt(m2);
    const double pn = norm(p);
    const Vec3 u{p[0] / pn, p[1] / pn, p[2] / pn};
    const double cos_alpha = u[0] * d[0] + u[1] * d[1] + u[2] * d[2];
    const Vec3 x{u[1] * d[2] - u[2] * d[1], u[2] * d[0] - u[0] * d[2], u[0] * d[1] - u[1] * d[0]};
    const double sin_alpha = norm(x);
    const double cos_beta = 1 / m, sin_beta = std::sqrt(m2 - 1) * cos_beta;
    const double denominator = cos_alpha * cos_beta - sin_alpha * sin_beta;
    if (denominator <= 0) return std::nullopt;
    magnitude = std::max(magnitude, 1 / denominator);
  }
  return Vec3{d[0] * magnitude, d[1] * magnitude, d[2] * magnitude};
}

double cesium_level_error(int level, int roots_x) {
  return kA * 2 * kPi * 0.25 / (65.0 * roots_x) / std::ldexp(1.0, level);
}

}  // namespace globe::web
