// RemoteReader: a package streamed from a server (docs/viewer.md "Remote
// sources"). Opened from a TileJSON URL whose "globe" member (what
// globe-serve publishes for every package: native_tiles.hpp there) gives the
// package's metadata, its tiles' URL template and each zoom's range of
// tiles; the tiles are the package's own blobs, so what is drawn is what the
// file would draw. Requests go through the process's one HttpClient
// (lib/net: priorities, retries, the disk cache): prefetch() asks for a batch
// at once, tile() waits for one. A 404 is an absent tile, asked once.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "data/tile_requests.hpp"
#include "net/http_client.hpp"
#include "tileformat/json.hpp"
#include "tileformat/tile_reader.hpp"

namespace globe::viewer {

class RemoteReader final : public tileformat::TileReader {
 public:
  // Reads the TileJSON at `url` (waiting for it). Throws InputError naming
  // the URL: unreachable, not JSON, or without a "globe" member (a foreign
  // TileJSON: the message says which sources the viewer reads).
  RemoteReader(const std::string& url, net::HttpClient& client);
  // From the TileJSON `doc` already read from `url`.
  RemoteReader(const std::string& url, const tileformat::JsonValue& doc, net::HttpClient& client);

  const std::map<std::string, std::string>& metadata() const override { return metadata_; }
  // Waits for the answer; nullopt for a 404/204; throws PackageError for a
  // tile that could not be had (naming the URL and why).
  std::optional<std::vector<uint8_t>> tile(tileformat::TileId id) override;
  // Inside its zoom's range and not answered 404.
  bool has_tile(tileformat::TileId id) override;
  // Every tile of the zoom's range (at most 65,536: a spread over it beyond).
  std::vector<tileformat::TileId> tile_ids(int zoom) override;
  const std::string& path() const override { return url_; }
  void prefetch(std::span<const tileformat::TileId> ids) override;
  void forget(std::span<const tileformat::TileId> ids) override;

  // The URL of a tile.
  std::string tile_url(tileformat::TileId id) const;

 private:
  struct Range {
    uint32_t min_x = 0, max_x = 0, min_y = 0, max_y = 0;
  };

  std::string url_, template_;
  std::map<std::string, std::string> metadata_;
  std::map<int, Range> zooms_;
  std::unique_ptr<TileRequests> requests_;
};

}  // namespace globe::viewer
