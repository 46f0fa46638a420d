// TileRequests: the tiles a remote source has asked its HttpClient for, by
// tile: prefetch() starts a request without waiting (later ones rank after
// earlier ones, as the loader will read them), take() waits for a tile's
// answer (asking first if nobody has), forget() cancels what is no longer
// wanted. A 404/204 is remembered: that tile is never asked again. Shared by
// every remote reader (remote_reader, xyz_fetcher, pmtiles_fetcher).
#pragma once

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "net/http_client.hpp"
#include "tileformat/tile_id.hpp"

namespace globe::viewer {

class TileRequests {
 public:
  // `accept_types`: the content types a tile may come as (others: broken).
  TileRequests(net::HttpClient& client, std::vector<std::string> accept_types);
  // Cancels what is pending and waits for the client to answer it.
  ~TileRequests();
  TileRequests(const TileRequests&) = delete;
  TileRequests& operator=(const TileRequests&) = delete;

  // `range`: "bytes=A-B" for a part of the URL (PMTiles), "" for all of it.
  void prefetch(tileformat::TileId id, const std::string& url, const std::string& range = "");
  // The body; nullopt for a 404/204; throws tileformat::PackageError naming
  // the URL and why for anything else (broken, failed, offline and absent).
  std::optional<std::vector<uint8_t>> take(tileformat::TileId id, const std::string& url,
                                           const std::string& range = "");
  void forget(tileformat::TileId id);
  // Whether the tile answered 404/204 already.
  bool absent(tileformat::TileId id);

 private:
  struct Pending {
    net::RequestId request = 0;
    bool done = false;
    net::Response response;
  };
  // Under mutex_.
  std::shared_ptr<Pending> ask(tileformat::TileId id, const std::string& url,
                               const std::string& range);

  net::HttpClient& client_;
  std::vector<std::string> accept_types_;
  std::mutex mutex_;
  std::condition_variable answered_;
  std::unordered_map<uint64_t, std::shared_ptr<Pending>> pending_;
  std::set<uint64_t> absent_;
  double next_priority_ = 0;
};

}  // namespace globe::viewer
