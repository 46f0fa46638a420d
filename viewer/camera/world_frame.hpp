// The viewer's coordinate systems, from the package's tiling:
//  - key units: int64 sample positions at the package's finest zoom, x east
//    and y south from the tiling's top-left corner. Every KPatch vertex at
//    every zoom is an integer point here, so shared vertices are exact.
//  - CRS coordinates of the tiling (metres for webmercator/local, degrees for
//    geodetic).
//  - world metres, relative to a view origin (a key point near the eye):
//    flat surface: a right-handed frame (x east, y north, z up) in metres
//    near the view latitude: webmercator heights are scaled by the Mercator
//    scale factor 1/cos(lat); geodetic degrees are scaled to metres.
//    globe surface: the WGS84 ellipsoid, in the east-north-up frame at the
//    origin's point on the ellipsoid (x east, y north, z up there), heights
//    in metres along the normal.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "tileformat/tiling.hpp"

namespace globe::viewer {

class ProjTransform;

struct KeyPoint {
  int64_t x = 0, y = 0;
  bool operator==(const KeyPoint&) const = default;
};

enum class Surface { kFlat, kGlobe };

// The globe frame's anchor: the view origin's point on the ellipsoid.
struct GlobeAnchor {
  KeyPoint origin;
  double lat = 0, lon = 0;  // radians
  double mercator_y = 0;    // webmercator: the origin's y / R
  glm::dvec3 ecef{0};
  glm::dmat3 enu{1};  // enu = M * (ecef - anchor ecef)
};

class WorldFrame {
 public:
  // steps: samples per block side - 1; key_zoom: the package's finest zoom.
  // Surface::kGlobe needs a geodetic or webmercator tiling (UsageError).
  WorldFrame(const tileformat::Tiling& tiling, int steps, int key_zoom,
             Surface surface = Surface::kFlat);
  ~WorldFrame();

  Surface surface() const { return surface_; }
  bool globe() const { return surface_ == Surface::kGlobe; }

  const tileformat::Tiling& tiling() const { return tiling_; }
  int key_zoom() const { return key_zoom_; }
  int steps() const { return steps_; }
  double crs_per_key() const { return crs_per_key_; }  // CRS units per key unit
  int64_t tile_size_keys(int z) const { return int64_t{steps_} << (key_zoom_ - z); }

  // Sets the latitude the metric scales are taken at (the view's).
  void set_view_latitude(double lat_deg);
  double metres_per_crs_x() const { return mx_; }
  double metres_per_crs_y() const { return my_; }
  double height_scale() const { return hz_; }  // world z per metre of height
  // The flat frame's scales at the view latitude on either surface: the
  // "ground" coordinates the deferred passes measure in (render/terrain_renderer.hpp).
  double ground_per_crs_x() const { return gx_; }
  double ground_per_crs_y() const { return gy_; }
  double ground_height_scale() const { return gz_; }

  glm::dvec2 key_to_crs(double kx, double ky) const;
  glm::dvec2 crs_to_key(double cx, double cy) const;
  // lon/lat (degrees) <-> tiling CRS; throw std::runtime_error if PROJ fails.
  glm::dvec2 lonlat_to_crs(double lon, double lat) const;
  glm::dvec2 crs_to_lonlat(double x, double y) const;

  // World metres of a key-unit point relative to `origin` (also key units).
  glm::dvec3 key_to_world(double kx, double ky, double height_m, const KeyPoint& origin) const {
    if (globe()) return globe_to_world(kx, ky, height_m, origin);
    return {(kx - double(origin.x)) * crs_per_key_ * mx_,
            -(ky - double(origin.y)) * crs_per_key_ * my_, height_m * hz_};
  }
  // Flat surface only: the key point under a world x/y.
  glm::dvec2 world_to_key(double wx, double wy, const KeyPoint& origin) const {
    return {double(origin.x) + wx / (crs_per_key_ * mx_),
            double(origin.y) - wy / (crs_per_key_ * my_)};
  }
  // Key point and height (metres) of a world point, on either surface.
  glm::dvec3 world_to_key_height(const glm::dvec3& w, const KeyPoint& origin) const;

  // Globe: lat/lon in radians of a key point (webmercator latitudes from
  // the inverse Gudermannian), geocentric metres of a key point and height,
  // and the anchor of `origin` (cached for the last origin asked for).
  glm::dvec2 key_to_latlon(double kx, double ky) const;
  glm::dvec3 key_to_ecef(double kx, double ky, double height_m) const;
  const GlobeAnchor& anchor(const KeyPoint& origin) const;

 private:
  glm::dvec3 globe_to_world(double kx, double ky, double height_m, const KeyPoint& origin) const;

  tileformat::Tiling tiling_;
  Surface surface_;
  int steps_, key_zoom_;
  mutable GlobeAnchor anchor_;
  mutable bool anchor_set_ = false;
  double crs_per_key_;
  bool geographic_ = false;
  double mx_ = 1, my_ = 1, hz_ = 1;
  double gx_ = 1, gy_ = 1, gz_ = 1;
  std::unique_ptr<ProjTransform> to_crs_, to_lonlat_;
};

}  // namespace globe::viewer
