// Coordinate systems of the viewer (see world_frame.hpp).
#include "camera/world_frame.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "camera/ellipsoid.hpp"
#include "camera/proj_crs.hpp"
#include "runtime/errors.hpp"

namespace globe::viewer {

namespace {
constexpr double kMetresPerDegreeLat = 110574.0;
constexpr double kMetresPerDegreeLonEquator = 111320.0;
}  // namespace

WorldFrame::WorldFrame(const tileformat::Tiling& tiling, int steps, int key_zoom, Surface surface)
    : tiling_(tiling),
      surface_(surface),
      steps_(steps),
      key_zoom_(key_zoom),
      crs_per_key_(tiling.sample_spacing(key_zoom, steps)) {
  geographic_ = crs_is_geographic(tiling.crs, "package CRS");
  if (surface_ == Surface::kGlobe && tiling.scheme != tileformat::Scheme::kGeodetic &&
      tiling.scheme != tileformat::Scheme::kWebMercator)
    throw UsageError(
        "--globe: the package is in a local CRS; the globe draws geodetic and webmercator "
        "packages (build one with --tiling geodetic or webmercator)");
  to_crs_ = std::make_unique<ProjTransform>("EPSG:4326", tiling.crs, "package CRS");
  to_lonlat_ = std::make_unique<ProjTransform>(tiling.crs, "EPSG:4326", "package CRS");
  set_view_latitude(0);
}

WorldFrame::~WorldFrame() = default;

void WorldFrame::set_view_latitude(double lat_deg) {
  const double c = std::cos(std::clamp(lat_deg, -85.0, 85.0) * std::numbers::pi / 180);
  if (tiling_.scheme == tileformat::Scheme::kWebMercator) {
    gx_ = gy_ = 1;
    gz_ = 1 / c;  // Mercator metres are stretched by 1/cos(lat); heights follow
  } else if (geographic_) {
    gx_ = kMetresPerDegreeLonEquator * c;
    gy_ = kMetresPerDegreeLat;
    gz_ = 1;
  } else {
    gx_ = gy_ = gz_ = 1;
  }
  if (globe()) {
    // Metres per CRS unit where they are largest (the equator): selection
    // distances and node sizes stay conservative at every latitude.
    mx_ = my_ = geographic_ ? wgs84::kA * std::numbers::pi / 180 : 1.0;
    hz_ = 1;
  } else {
    mx_ = gx_, my_ = gy_, hz_ = gz_;
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

glm::dvec2 WorldFrame::key_to_latlon(double kx, double ky) const {
  const glm::dvec2 c = key_to_crs(kx, ky);
  constexpr double d = std::numbers::pi / 180;
  if (tiling_.scheme == tileformat::Scheme::kWebMercator)
    return {std::atan(std::sinh(c.y / wgs84::kA)), c.x / wgs84::kA};
  return {c.y * d, c.x * d};
}

glm::dvec3 WorldFrame::key_to_ecef(double kx, double ky, double height_m) const {
  const glm::dvec2 ll = key_to_latlon(kx, ky);
  return wgs84::to_ecef(ll.x, ll.y, height_m);
}

const GlobeAnchor& WorldFrame::anchor(const KeyPoint& origin) const {
  if (anchor_set_ && anchor_.origin == origin) return anchor_;
  GlobeAnchor a;
  a.origin = origin;
  const glm::dvec2 ll = key_to_latlon(double(origin.x), double(origin.y));
  a.lat = ll.x, a.lon = ll.y;
  a.mercator_y = key_to_crs(double(origin.x), double(origin.y)).y / wgs84::kA;
  a.ecef = wgs84::to_ecef(a.lat, a.lon, 0);
  a.enu = wgs84::enu_rotation(a.lat, a.lon);
  anchor_ = a;
  anchor_set_ = true;
  return anchor_;
}

glm::dvec3 WorldFrame::globe_to_world(double kx, double ky, double height_m,
                                      const KeyPoint& origin) const {
  const GlobeAnchor& a = anchor(origin);
  return a.enu * (key_to_ecef(kx, ky, height_m) - a.ecef);
}

glm::dvec3 WorldFrame::world_to_key_height(const glm::dvec3& w, const KeyPoint& origin) const {
  if (!globe()) {
    const glm::dvec2 k = world_to_key(w.x, w.y, origin);
    return {k.x, k.y, w.z / hz_};
  }
  const GlobeAnchor& a = anchor(origin);
  const glm::dvec3 llh = wgs84::from_ecef(a.ecef + glm::transpose(a.enu) * w);
  constexpr double d = 180 / std::numbers::pi;
  // Longitudes continue past +-180 degrees from the origin's side.
  double lon = llh.y;
  while (lon - a.lon > std::numbers::pi)
    lon -= 2 * std::numbers::pi;
  while (lon - a.lon < -std::numbers::pi)
    lon += 2 * std::numbers::pi;
  glm::dvec2 crs = tiling_.scheme == tileformat::Scheme::kWebMercator
                       ? glm::dvec2(lon * wgs84::kA, wgs84::kA * std::atanh(std::sin(llh.x)))
                       : glm::dvec2(lon * d, llh.x * d);
  const glm::dvec2 k = crs_to_key(crs.x, crs.y);
  return {k.x, k.y, llh.z};
}

}  // namespace globe::viewer
