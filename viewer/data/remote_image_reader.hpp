// RemoteImageReader: imagery from a foreign tile server (an XYZ template or
// a PMTiles archive, through a RasterTileFetcher) read as an image package:
// web mercator, the tiles' bytes as served (PNG, JPEG or WebP, which the
// image cache decodes), the tile size and colour read off the first tile.
// Its metadata is what tileformat::to_metadata writes for an image package,
// so the image layers draw it as one (docs/viewer.md "Remote sources").
#pragma once

#include <map>
#include <memory>
#include <string>

#include "data/raster_tile_fetcher.hpp"
#include "tileformat/tile_reader.hpp"

namespace globe::viewer {

class RemoteImageReader final : public tileformat::TileReader {
 public:
  // Reads one tile of the coarsest zoom for its size and colour; throws
  // InputError naming the source when none can be read or decoded.
  explicit RemoteImageReader(std::unique_ptr<RasterTileFetcher> fetcher);

  const std::map<std::string, std::string>& metadata() const override { return metadata_; }
  std::optional<std::vector<uint8_t>> tile(tileformat::TileId id) override;
  bool has_tile(tileformat::TileId id) override;
  std::vector<tileformat::TileId> tile_ids(int zoom) override;
  const std::string& path() const override { return fetcher_->name(); }
  void prefetch(std::span<const tileformat::TileId> ids) override { fetcher_->prefetch(ids); }

 private:
  std::unique_ptr<RasterTileFetcher> fetcher_;
  std::map<std::string, std::string> metadata_;
};

// The tiles of zoom z of a web mercator source inside `bounds` (W, S, E, N
// degrees), in (y, x) order; at most 65,536 (a spread over them beyond).
std::vector<tileformat::TileId> webmercator_tiles_in(int z, const std::array<double, 4>& bounds);
// Whether tile `id` of web mercator intersects `bounds`.
bool webmercator_tile_in(tileformat::TileId id, const std::array<double, 4>& bounds);

}  // namespace globe::viewer
