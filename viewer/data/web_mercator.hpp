// EPSG:3857 metres of a longitude / latitude in degrees, latitude clamped to
// the tiling's +-85.0511: the bounds of the remote elevation sources
// (raster_dem_reader, quantized_mesh_reader, block_synthesizer).
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "tileformat/tiling.hpp"

namespace globe::viewer {

inline double mercator_x(double lon_deg) {
  return lon_deg * (tileformat::kWebMercatorHalf / 180.0);
}
inline double mercator_y(double lat_deg) {
  constexpr double pi = std::numbers::pi;
  const double lat =
      std::clamp(lat_deg, -tileformat::kWebMercatorMaxLat, tileformat::kWebMercatorMaxLat);
  return tileformat::kWebMercatorHalf / pi * std::log(std::tan(pi / 4 + lat * pi / 360));
}

}  // namespace globe::viewer
