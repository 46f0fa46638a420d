// The viewer's network: one HttpClient for the process (lib/net), made when
// the first URL is opened, and the opener that lets lib/runtime's
// open_*_package read URLs as RemoteReaders (docs/viewer.md "Remote
// sources"). Lives in main() for the whole run, so every reader outlives
// nothing it needs.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "data/remote_open.hpp"
#include "net/http_client.hpp"

namespace globe::viewer {

struct NetworkSettings {
  std::string cache_dir;  // "" = $XDG_CACHE_HOME/globe-view or ~/.cache/globe-view
  bool no_cache = false;  // --cache-dir none
  uint64_t cache_mb = 1024;
  bool offline = false;
  int max_connections_per_host = 6;
  RemoteOptions remote;  // --dem-encoding, --source-zooms
};

// The cache folder a run uses (the default resolved).
std::string resolve_cache_dir(const NetworkSettings& s);

class Network {
 public:
  // Registers the URL opener with lib/runtime; unregisters in the destructor.
  explicit Network(NetworkSettings settings);
  ~Network();
  Network(const Network&) = delete;
  Network& operator=(const Network&) = delete;

  // The client, made on first use (throws NetError: the cache folder).
  net::HttpClient& client();
  // Totals so far; nullopt when no URL was opened.
  std::optional<net::ClientStats> stats();

  // The process's network, while one exists (for --stats); else nullptr.
  static Network* current();

 private:
  NetworkSettings settings_;
  std::mutex mutex_;
  std::unique_ptr<net::HttpClient> client_;
};

}  // namespace globe::viewer
