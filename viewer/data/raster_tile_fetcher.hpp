// RasterTileFetcher: where a remote source's encoded raster tiles come from —
// an XYZ URL template (xyz_fetcher.hpp) or a PMTiles archive over HTTP ranges
// (pmtiles_fetcher.hpp) — in web mercator XYZ numbering (row 0 at the
// north). Imagery readers hand the bytes to the image decoders as they are;
// the raster-DEM reader (raster_dem_reader.hpp) decodes them into heights.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tileformat/tile_id.hpp"

namespace globe::viewer {

class RasterTileFetcher {
 public:
  virtual ~RasterTileFetcher() = default;
  // The tile's bytes (PNG, JPEG or WebP as served), or nullopt where the
  // source has none (404/204, outside its zooms). Waits for the answer;
  // throws tileformat::PackageError naming the URL for a tile that could not
  // be had. Thread-safe.
  virtual std::optional<std::vector<uint8_t>> fetch(tileformat::TileId id) = 0;
  // These will be fetched soon, the first most urgent (requests start now).
  virtual void prefetch(std::span<const tileformat::TileId> ids) { (void)ids; }
  virtual int min_zoom() const = 0;
  virtual int max_zoom() const = 0;
  // West, south, east, north in degrees: where the source has tiles.
  virtual std::array<double, 4> bounds() const {
    return {-180, -85.0511287798, 180, 85.0511287798};
  }
  // The URL (for messages and as the reader's path()).
  virtual const std::string& name() const = 0;
};

}  // namespace globe::viewer
