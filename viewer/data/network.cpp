// The viewer's network (see network.hpp).
#include "data/network.hpp"

#include <cstdlib>

#include "data/remote_open.hpp"
#include "runtime/errors.hpp"
#include "runtime/package_open.hpp"

namespace globe::viewer {
namespace {

Network* g_current = nullptr;

}  // namespace

std::string resolve_cache_dir(const NetworkSettings& s) {
  if (!s.cache_dir.empty()) return s.cache_dir;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::string(x) + "/globe-view";
  if (const char* h = std::getenv("HOME"); h && *h) return std::string(h) + "/.cache/globe-view";
  return ".globe-view-cache";
}

Network::Network(NetworkSettings settings) : settings_(std::move(settings)) {
  g_current = this;
  set_remote_opener([this](const std::string& url) -> std::unique_ptr<tileformat::TileReader> {
    return open_remote(url, client(), settings_.remote);
  });
}

Network::~Network() {
  set_remote_opener(nullptr);
  g_current = nullptr;
}

Network* Network::current() {
  return g_current;
}

net::HttpClient& Network::client() {
  std::lock_guard lock(mutex_);
  if (!client_) {
    net::ClientOptions o;
    o.user_agent = std::string("globe-view/") + GLOBE_VERSION;
    o.max_connections_per_host = settings_.max_connections_per_host;
    o.cache_dir = settings_.no_cache ? "" : resolve_cache_dir(settings_);
    o.cache_max_bytes = settings_.cache_mb << 20;
    o.offline = settings_.offline;
    try {
      client_ = std::make_unique<net::HttpClient>(std::move(o));
    } catch (const net::NetError& e) {  // the cache folder: the user's to fix
      throw InputError(std::string(e.what()) + " (--cache-dir DIR elsewhere, or none)");
    }
  }
  return *client_;
}

std::optional<net::ClientStats> Network::stats() {
  std::lock_guard lock(mutex_);
  if (!client_) return std::nullopt;
  return client_->stats();
}

}  // namespace globe::viewer
