// Crossing between a layer's tiling and the terrain's (see layer_tiling.hpp).
#include "camera/layer_tiling.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace globe::viewer {

namespace {

using tileformat::Scheme;

double rad(double d) {
  return d * std::numbers::pi / 180;
}
double deg(double r) {
  return r * 180 / std::numbers::pi;
}

bool close(double a, double b) {
  return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(a) + std::abs(b));
}

}  // namespace

CrsCross crs_cross(const tileformat::Tiling& terrain, const tileformat::Tiling& layer) {
  if (terrain.scheme == layer.scheme) return CrsCross::kSame;
  if (terrain.scheme == Scheme::kGeodetic && layer.scheme == Scheme::kWebMercator)
    return CrsCross::kGeodeticToMercator;
  if (terrain.scheme == Scheme::kWebMercator && layer.scheme == Scheme::kGeodetic)
    return CrsCross::kMercatorToGeodetic;
  return CrsCross::kOther;
}

CrossAnchor cross_anchor(CrsCross cross, glm::dvec2 o) {
  CrossAnchor a{o, {0, 0}};
  if (cross == CrsCross::kGeodeticToMercator) {
    const double lat = std::clamp(o.y, -kMaxMercatorLat, kMaxMercatorLat);
    a.anchor = {kMercatorR * rad(o.x), kMercatorR * std::atanh(std::sin(rad(lat)))};
    a.param = {static_cast<float>(rad(lat)), static_cast<float>(kMercatorR)};
  } else if (cross == CrsCross::kMercatorToGeodetic) {
    a.anchor = {deg(o.x / kMercatorR), deg(std::atan(std::sinh(o.y / kMercatorR)))};
    a.param = {static_cast<float>(o.y / kMercatorR), static_cast<float>(kMercatorR)};
  }
  return a;
}

glm::dvec2 layer_to_terrain_crs(CrsCross cross, glm::dvec2 c) {
  if (cross == CrsCross::kGeodeticToMercator)  // the layer is webmercator
    return {deg(c.x / kMercatorR), deg(std::atan(std::sinh(c.y / kMercatorR)))};
  if (cross == CrsCross::kMercatorToGeodetic) {  // the layer is geodetic
    const double lat = std::clamp(c.y, -kMaxMercatorLat, kMaxMercatorLat);
    return {kMercatorR * rad(c.x), kMercatorR * std::atanh(std::sin(rad(lat)))};
  }
  return c;
}

LayerTiling::LayerTiling(const tileformat::Tiling& layer, CrsCross cross, const WorldFrame& world)
    : layer_(layer), cross_(cross), world_(world) {
  const tileformat::Tiling& t = world.tiling();
  same_grid_ = cross == CrsCross::kSame && close(t.origin_x, layer.origin_x) &&
               close(t.origin_y, layer.origin_y) && close(t.root_size, layer.root_size);
}

glm::dvec2 LayerTiling::tile_to_key(int z, double tx, double ty) const {
  if (same_grid_) {
    const double keys = double(world_.steps()) * std::ldexp(1.0, world_.key_zoom() - z);
    return {tx * keys, ty * keys};
  }
  const double size = layer_.tile_size(z);
  const glm::dvec2 c =
      layer_to_terrain_crs(cross_, {layer_.origin_x + tx * size, layer_.origin_y - ty * size});
  return world_.crs_to_key(c.x, c.y);
}

}  // namespace globe::viewer
