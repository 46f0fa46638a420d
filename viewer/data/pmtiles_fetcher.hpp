// PmtilesFetcher: raster tiles of a PMTiles v3 archive on any HTTP server
// that answers byte ranges (static hosting): the header and root directory
// in one 16 KiB read when the archive is opened, leaf directories read once
// and kept, each tile one range request (lib/tileformat's pmtiles_read.hpp
// decodes; the requests go through the process's HttpClient and its disk
// cache). Imagery (PNG, JPEG, WebP tiles) and, with --dem-encoding, raster
// DEMs; vector (MVT) archives are refused with what to do instead.
#pragma once

#include <array>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "data/raster_tile_fetcher.hpp"
#include "data/tile_requests.hpp"
#include "net/http_client.hpp"
#include "tileformat/pmtiles_read.hpp"

namespace globe::viewer {

class PmtilesFetcher final : public RasterTileFetcher {
 public:
  // Reads the header and root directory; throws InputError naming the URL:
  // unreachable, not PMTiles v3, vector tiles, or compressed in a way not read.
  PmtilesFetcher(std::string url, net::HttpClient& client);

  std::optional<std::vector<uint8_t>> fetch(tileformat::TileId id) override;
  void prefetch(std::span<const tileformat::TileId> ids) override;
  int min_zoom() const override { return header_.info.min_zoom; }
  int max_zoom() const override { return header_.info.max_zoom; }
  std::array<double, 4> bounds() const override;
  const std::string& name() const override { return url_; }

  tileformat::pmtiles::TileType tile_type() const { return header_.info.tile_type; }
  // The archive's JSON metadata (read on first call).
  std::string metadata_json();

 private:
  // The entry of a tile, reading leaf directories as needed (when `may_wait`;
  // else nullopt if a leaf is not read yet). nullopt also where there is none.
  std::optional<tileformat::pmtiles::Entry> entry_of(uint64_t tile_id, bool may_wait);
  std::vector<uint8_t> read_range(uint64_t offset, uint64_t length, const std::string& what);
  std::vector<uint8_t> uncompress(std::vector<uint8_t> bytes, tileformat::pmtiles::Compression c,
                                  const std::string& what) const;

  std::string url_;
  net::HttpClient& client_;
  tileformat::pmtiles::Header header_;
  std::vector<tileformat::pmtiles::Entry> root_;
  std::mutex mutex_;
  std::map<uint64_t, std::vector<tileformat::pmtiles::Entry>> leaves_;  // by offset
  std::unique_ptr<TileRequests> requests_;
};

}  // namespace globe::viewer
