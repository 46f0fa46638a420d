// quantized-mesh-1.0 (CesiumGS/quantized-mesh): the tile encoder and the
// WGS84 geometry its header needs (docs/web.md "Quantized-mesh"). Written from
// the specification; the tests decode with an independent reader
// (tests/spec_readers/quantized_mesh_reader.hpp).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace globe::web {

using Vec3 = std::array<double, 3>;

inline constexpr int kQuantizedMax = 32767;

// One tile, ready to encode: vertices numbered in the order the triangle list
// first uses them (the index coding needs it), triangles counter-clockwise.
struct QuantizedMeshTile {
  Vec3 center{};  // ECEF metres
  float min_height = 0, max_height = 0;
  Vec3 sphere_center{};
  double sphere_radius = 0;
  Vec3 horizon_point{};                            // ellipsoid-scaled ECEF
  std::vector<uint16_t> u, v, height;              // 0..32767
  std::vector<uint32_t> triangles;                 // 3 per triangle
  std::vector<uint32_t> west, south, east, north;  // edge vertices
  std::vector<uint8_t> oct_normals;                // 2 per vertex, or empty
  std::vector<uint8_t> water_mask;                 // 1 or 256 x 256 bytes, or empty
};

// The tile's bytes (not gzipped). Throws std::invalid_argument if the
// triangle list does not introduce vertices in order.
std::vector<uint8_t> encode_quantized_mesh(const QuantizedMeshTile& tile);

// WGS84: geodetic degrees and metres to Earth-centred, Earth-fixed metres.
Vec3 ecef(double lon_deg, double lat_deg, double height_m);
// The same in two halves, for grids whose longitudes and latitudes repeat
// along columns and rows: the trigonometry of each computed once, the
// positions bit for bit those of ecef().
struct EcefLongitude {
  double c, s;  // cos, sin
};
struct EcefLatitude {
  double c, s, n;  // cos, sin, prime vertical radius
};
EcefLongitude ecef_longitude(double lon_deg);
EcefLatitude ecef_latitude(double lat_deg);
Vec3 ecef(const EcefLongitude& lon, const EcefLatitude& lat, double height_m);
// The ellipsoid's outward unit normal at a longitude and latitude.
Vec3 ellipsoid_normal(double lon_deg, double lat_deg);
// Cigolle et al.'s octahedral coding of a unit vector in two bytes, as Cesium
// decodes it (0..255 onto -1..1).
std::array<uint8_t, 2> oct_encode(const Vec3& unit);
// Cesium's horizon-culling point: a point in ellipsoid-scaled space along
// `direction` (ECEF) such that whenever it is below the horizon, every one of
// `positions` is; nullopt if no point along that direction works (a tile
// spanning half the globe).
std::optional<Vec3> horizon_occlusion_point(const std::vector<Vec3>& positions,
                                            const Vec3& direction);
// CesiumJS's geometric error of a terrain level: the Earth's equatorial
// circumference / 4 / (65 * tiles across at level 0) / 2^level, in metres
// (TerrainProvider.getEstimatedLevelZeroGeometricErrorForAHeightmap).
double cesium_level_error(int level, int roots_x);

}  // namespace globe::web
