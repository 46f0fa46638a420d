// The polygons of an OGR source burnt into byte masks of longitude/latitude
// boxes (quantized-mesh water masks, docs/web.md): every polygon layer read
// once, reprojected to EPSG:4326 (longitude, latitude), then rasterized by
// GDAL per box. Thread-safe.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace globe {

class PolygonMask {
 public:
  // Throws InputError naming the file if it cannot be read, has no polygons
  // or no CRS.
  explicit PolygonMask(const std::string& path);
  ~PolygonMask();
  PolygonMask(const PolygonMask&) = delete;
  PolygonMask& operator=(const PolygonMask&) = delete;

  // size x size bytes, rows north to south, columns west to east, each 255
  // where the pixel's centre lies in a polygon and 0 elsewhere.
  std::vector<uint8_t> rasterize(double west, double south, double east, double north, int size);
  size_t polygons() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::mutex mutex_;
};

}  // namespace globe
