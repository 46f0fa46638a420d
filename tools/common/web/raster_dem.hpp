// Raster-DEM tiles for web maps (docs/web.md "Terrarium and Terrain-RGB"):
// heights in the RGB of PNG pixels, in web mercator XYZ tiles, as MapLibre
// GL's raster-dem sources read them.
//   Mapzen Terrarium:  h = R * 256 + G + B / 256 - 32768       (1/256 m steps)
//   Mapbox Terrain-RGB: h = -10000 + (R * 65536 + G * 256 + B) * 0.1   (0.1 m)
// Heights outside what a pixel can hold are clamped. Pixel (i, j) of a tile
// is the area square whose centre is sampled, (i + 0.5, j + 0.5) / size of
// the tile from its top-left corner.
#pragma once

#include <cstdint>
#include <string>

namespace globe::web {

enum class DemEncoding { kTerrarium, kTerrainRgb };

// "terrarium" or "mapbox" (the names MapLibre's `encoding` takes).
const char* encoding_name(DemEncoding e);
// `h` metres -> 3 bytes at `rgb`.
void encode_dem_pixel(double h, DemEncoding e, uint8_t* rgb);
// The height a pixel holds (the decoder of the formulas above).
double decode_dem_pixel(const uint8_t* rgb, DemEncoding e);

// Web mercator (EPSG:3857, sphere of 6378137 m): the edge of the world.
inline constexpr double kMercatorHalf = 20037508.342789244;
struct MercatorPoint {
  double x = 0, y = 0;
};
// The centre of pixel (i, j) of XYZ tile (z, x, y) of `size` pixels.
MercatorPoint pixel_centre(int z, uint32_t x, uint32_t y, int size, int i, int j);
// Degrees of a web mercator point, and back.
void mercator_to_lonlat(MercatorPoint p, double& lon, double& lat);
MercatorPoint lonlat_to_mercator(double lon, double lat);

}  // namespace globe::web
