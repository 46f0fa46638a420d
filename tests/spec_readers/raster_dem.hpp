// Independent decoders for RGB-encoded elevation tiles and the Web Mercator
// (XYZ / "slippy map") tile grid, written from their public definitions. The
// tests use them to check DEM tiles the project writes; no project code is used.
//
//  * Mapzen Terrarium (tilezen/joerd docs/formats.md; also PMTiles spec v3
//    section 5, metadata "encoding": "terrarium"):
//        height = (R * 256 + G + B / 256) - 32768      metres
//  * Mapbox Terrain-RGB (Mapbox "Terrain-RGB" / "Terrain-DEM v1" docs):
//        height = -10000 + (R * 256 * 256 + G * 256 + B) * 0.1   metres
//  * Web Mercator XYZ tiles (OpenStreetMap wiki "Slippy map tilenames",
//    EPSG:3857): 2^z x 2^z tiles, x from west (-180) to east, y (rows) from
//    north (+85.0511 degrees) to south, pixel (0, 0) at the north-west corner.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace spec_readers::raster_dem {

constexpr double kPi = 3.14159265358979323846;
// Latitude where the square Web Mercator world ends: atan(sinh(pi)).
constexpr double kMaxMercatorLatitude = 85.05112877980659;

// Terrarium: h = R * 256 + G + B / 256 - 32768.
inline double terrarium_height(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  return r * 256.0 + g + b / 256.0 - 32768.0;
}

// Terrain-RGB: h = -10000 + (R * 65536 + G * 256 + B) * 0.1.
inline double terrain_rgb_height(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  return -10000.0 + (r * 65536.0 + g * 256.0 + b) * 0.1;
}

enum class Encoding { Terrarium, TerrainRgb };

// Height of pixel (px, py) in an interleaved 8-bit image with `channels`
// channels per pixel (3 = RGB, 4 = RGBA; alpha is ignored), rows top to bottom.
inline double pixel_height(const std::uint8_t* pixels, int width, int height, int channels, int px,
                           int py, Encoding encoding) {
  if (channels < 3) throw std::runtime_error("raster-dem: need at least 3 channels (R, G, B)");
  if (px < 0 || py < 0 || px >= width || py >= height) {
    throw std::runtime_error("raster-dem: pixel (" + std::to_string(px) + ", " +
                             std::to_string(py) + ") is outside the " + std::to_string(width) +
                             "x" + std::to_string(height) + " image");
  }
  const std::uint8_t* p =
      pixels + (static_cast<std::size_t>(py) * width + static_cast<std::size_t>(px)) * channels;
  return encoding == Encoding::Terrarium ? terrarium_height(p[0], p[1], p[2])
                                         : terrain_rgb_height(p[0], p[1], p[2]);
}

struct LonLat {
  double lon_deg = 0, lat_deg = 0;
};

// Global Web Mercator coordinates in units of tiles at zoom z: (0, 0) is the
// north-west corner of the world, (2^z, 2^z) the south-east one.
inline LonLat lon_lat_from_tile_coords(int z, double tx, double ty) {
  const double n = std::ldexp(1.0, z);
  LonLat out;
  out.lon_deg = tx / n * 360.0 - 180.0;
  out.lat_deg = std::atan(std::sinh(kPi * (1.0 - 2.0 * ty / n))) * 180.0 / kPi;
  return out;
}

// Centre of pixel (px, py) of tile z/x/y (XYZ rows, y = 0 at the north) in a
// tile of tile_size x tile_size pixels (256 or 512): the centre sits half a
// pixel in from the pixel's north-west corner.
inline LonLat pixel_center_lon_lat(int z, std::uint32_t x, std::uint32_t y, int px, int py,
                                   int tile_size = 256) {
  if (tile_size <= 0) throw std::runtime_error("raster-dem: tile size must be positive");
  return lon_lat_from_tile_coords(z, x + (px + 0.5) / tile_size, y + (py + 0.5) / tile_size);
}

struct TilePixel {
  std::uint32_t x = 0, y = 0;  // tile column and row (XYZ)
  int px = 0, py = 0;          // pixel inside the tile, (0, 0) at its north-west
};

// Tile and pixel containing (lon, lat) at zoom z. Points exactly on the east
// or south edge of the world fall in the last column / row. Throws for
// latitudes beyond +-85.0511 degrees (outside the Web Mercator square) and
// longitudes outside -180..180.
inline TilePixel tile_pixel_from_lon_lat(int z, double lon_deg, double lat_deg,
                                         int tile_size = 256) {
  if (tile_size <= 0) throw std::runtime_error("raster-dem: tile size must be positive");
  if (!(std::abs(lat_deg) <= kMaxMercatorLatitude) || !(std::abs(lon_deg) <= 180.0)) {
    throw std::runtime_error("raster-dem: (" + std::to_string(lon_deg) + ", " +
                             std::to_string(lat_deg) + ") is outside the Web Mercator world");
  }
  const double n = std::ldexp(1.0, z);
  const double lat = lat_deg * kPi / 180.0;
  // x = (lon + 180) / 360 * n;  y = (1 - asinh(tan(lat)) / pi) / 2 * n.
  const double total_pixels = n * tile_size;
  const double gx = (lon_deg + 180.0) / 360.0 * total_pixels;
  const double gy = (1.0 - std::asinh(std::tan(lat)) / kPi) / 2.0 * total_pixels;
  auto to_pixel = [total_pixels](double g) {
    double p = std::floor(g);
    if (p < 0) p = 0;
    if (p > total_pixels - 1) p = total_pixels - 1;
    return static_cast<std::uint64_t>(p);
  };
  const std::uint64_t gpx = to_pixel(gx), gpy = to_pixel(gy);
  TilePixel out;
  out.x = static_cast<std::uint32_t>(gpx / tile_size);
  out.y = static_cast<std::uint32_t>(gpy / tile_size);
  out.px = static_cast<int>(gpx % tile_size);
  out.py = static_cast<int>(gpy % tile_size);
  return out;
}

}  // namespace spec_readers::raster_dem
