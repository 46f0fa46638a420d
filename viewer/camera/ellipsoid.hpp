// The WGS84 ellipsoid in double precision, for the globe frame
// (docs/viewer.md "Globe"): geodetic <-> geocentric (ECEF) coordinates and
// the local east-north-up frame at a point. CPU side only; the vertex shader
// has its own float form of the same mapping (render/globe_glsl.hpp).
#pragma once

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace globe::viewer::wgs84 {

inline constexpr double kA = 6378137.0;                   // semi-major axis, metres
inline constexpr double kE2 = 0.00669437999014132;        // first eccentricity squared
inline constexpr double kB = 6356752.314245179;           // semi-minor axis
inline constexpr double kMercatorMaxLat = 85.0511287798;  // webmercator's edge, degrees

// Prime vertical radius of curvature N(lat).
double prime_vertical_radius(double lat_rad);

// Geocentric metres of (lat, lon) in radians and height h above the ellipsoid.
glm::dvec3 to_ecef(double lat_rad, double lon_rad, double h);

// (lat_rad, lon_rad, h) of a geocentric point (iterated to < 1e-12 rad).
glm::dvec3 from_ecef(const glm::dvec3& p);

// Rows: east, north, up at (lat, lon); enu = M * (ecef - origin).
glm::dmat3 enu_rotation(double lat_rad, double lon_rad);

}  // namespace globe::viewer::wgs84
