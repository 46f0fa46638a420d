// A layer package's tiling seen from the terrain's (docs/viewer.md "Layers
// in another tiling"): imagery, lines and points may be tiled in another
// scheme than the terrain they are drawn over. Between geodetic and
// webmercator the crossing is in closed form, here in double for the CPU
// (chart places, point tile selection, the shaders' anchors) and in
// render/crs_cross_glsl.hpp for the GPU, which carries offsets from an
// anchor near the eye so that float stays exact enough.
#pragma once

#include <glm/vec2.hpp>

#include "camera/world_frame.hpp"
#include "tileformat/tile_id.hpp"
#include "tileformat/tiling.hpp"

namespace globe::viewer {

// How points of the terrain's CRS reach a layer's (the values are the
// shaders' mode numbers). kOther: a pair of CRSs without a closed form
// (local tilings); imagery crosses those through a PROJ grid.
enum class CrsCross : int {
  kSame = 0,
  kGeodeticToMercator = 1,
  kMercatorToGeodetic = 2,
  kOther = 3
};

// kSame for the same scheme (local tilings: the caller compares CRSs).
CrsCross crs_cross(const tileformat::Tiling& terrain, const tileformat::Tiling& layer);

inline constexpr double kMercatorR = 6378137.0;           // webmercator sphere
inline constexpr double kMaxMercatorLat = 85.0511287798;  // degrees

// The layer CRS point of terrain CRS point `terrain` (latitudes clamped to
// webmercator's), and the shaders' parameter for offsets from it
// (kGeodeticToMercator: (lat0 radians, R); kMercatorToGeodetic: (y0 / R, R)).
struct CrossAnchor {
  glm::dvec2 anchor{0};
  glm::vec2 param{0};
};
CrossAnchor cross_anchor(CrsCross cross, glm::dvec2 terrain);

// A layer CRS point in the terrain's CRS (kSame and kOther: unchanged).
glm::dvec2 layer_to_terrain_crs(CrsCross cross, glm::dvec2 layer);

// Tile coordinates of a layer (fractional tiles of zoom z, y south) as the
// terrain's key units: exact integer arithmetic when both share a tiling,
// through the CRSs otherwise.
class LayerTiling {
 public:
  LayerTiling(const tileformat::Tiling& layer, CrsCross cross, const WorldFrame& world);
  glm::dvec2 tile_to_key(int z, double tx, double ty) const;
  glm::dvec2 tile_to_key(tileformat::TileId id, double fx, double fy) const {
    return tile_to_key(id.z, id.x + fx, id.y + fy);
  }
  CrsCross cross() const { return cross_; }

 private:
  tileformat::Tiling layer_;
  CrsCross cross_;
  const WorldFrame& world_;
  bool same_grid_ = false;
};

}  // namespace globe::viewer
