// Raster-DEM pixel codings and web mercator geometry (see raster_dem.hpp).
#include "web/raster_dem.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace globe::web {

namespace {
constexpr double kRadius = 6378137.0;
}

const char* encoding_name(DemEncoding e) {
  return e == DemEncoding::kTerrarium ? "terrarium" : "mapbox";
}

void encode_dem_pixel(double h, DemEncoding e, uint8_t* rgb) {
  if (!std::isfinite(h)) h = 0;
  uint32_t v;
  if (e == DemEncoding::kTerrarium) {
    // Units of 1/256 m from -32768 m: R, G whole metres, B the fraction.
    v = static_cast<uint32_t>(std::clamp(std::lround((h + 32768.0) * 256.0), 0L, 0xffffffL));
  } else {
    v = static_cast<uint32_t>(std::clamp(std::lround((h + 10000.0) * 10.0), 0L, 0xffffffL));
  }
  rgb[0] = static_cast<uint8_t>(v >> 16);
  rgb[1] = static_cast<uint8_t>(v >> 8);
  rgb[2] = static_cast<uint8_t>(v);
}

double decode_dem_pixel(const uint8_t* rgb, DemEncoding e) {
  if (e == DemEncoding::kTerrarium) return rgb[0] * 256.0 + rgb[1] + rgb[2] / 256.0 - 32768.0;
  return -10000.0 + (rgb[0] * 65536.0 + rgb[1] * 256.0 + rgb[2]) * 0.1;
}

MercatorPoint pixel_centre(int z, uint32_t x, uint32_t y, int size, int i, int j) {
  const double tile = 2 * kMercatorHalf / std::ldexp(1.0, z);
  return {-kMercatorHalf + (x + (i + 0.5) / size) * tile,
          kMercatorHalf - (y + (j + 0.5) / size) * tile};
}

void mercator_to_lonlat(MercatorPoint p, double& lon, double& lat) {
  lon = p.x / kRadius * 180 / std::numbers::pi;
  lat = std::atan(std::sinh(p.y / kRadius)) * 180 / std::numbers::pi;
}

MercatorPoint lonlat_to_mercator(double lon, double lat) {
  const double phi = std::clamp(lat, -89.999999, 89.999999) * std::numbers::pi / 180;
  return {lon * std::numbers::pi / 180 * kRadius, std::asinh(std::tan(phi)) * kRadius};
}

}  // namespace globe::web
