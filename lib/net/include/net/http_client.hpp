// HttpClient: the viewer's one door to the network — libcurl's multi
// interface (HTTP/1.1 and HTTP/2 where offered) on a thread of its own, with
// a priority queue in front of it, a per-host connection cap, retries with
// exponential backoff, 429 Retry-After honoured per host, HTTP caching
// (revalidation with ETag / Last-Modified, Cache-Control / Expires) through a
// DiskCache, and counters for --stats. No GL, no GDAL, nothing else of the
// project. libcurl is called from src/curl_multi.cpp only.
//
// Semantics (docs/viewer.md "Remote sources"):
// - 2xx with a body that passes the request's checks (content type, the
//   caller's validate): kOk, stored in the cache unless `no-store`.
// - 404, 410, 204: kNoContent; never retried; a URL that answered so is
//   answered kNoContent again for the rest of the client's life without a
//   request (no 404 storms).
// - 5xx, 408, timeouts, connection resets, truncated bodies (fewer bytes than
//   Content-Length), a transfer slower than the low-speed limit: retried with
//   exponential backoff (initial, doubled, capped; full jitter from a seeded
//   generator) up to max_retries, then kFailed.
// - 429 (and 503 with Retry-After): no request to that host until the time
//   Retry-After gives (seconds or an HTTP date; without one, the backoff);
//   then retried; counted as a retry.
// - 2xx whose Content-Type is not one of accept_types, or that `validate`
//   rejects: kBroken, not cached, not retried, reported once per URL on
//   the log callback.
// - Other 4xx: kFailed, not retried.
// - Cache: a fresh entry (max-age / Expires not passed) is answered without a
//   request (from_cache); a stale one with a validator is revalidated
//   (If-None-Match / If-Modified-Since; a 304 refreshes it and answers its
//   body, from_cache and revalidated); without a validator, fetched again.
//   `offline`: only the cache answers, stale or not; a miss is kOffline.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace globe::net {

// Every error of lib/net that is not an outcome of a request: a cache file
// that cannot be opened or created, libcurl failing to start. The message
// names the file or URL and what to do.
struct NetError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct ClientOptions {
  std::string user_agent = "globe-view";  // the program and its version, e.g. "globe-view/0.1.0"
  int max_connections_per_host = 6;
  int max_connections = 24;  // over all hosts
  double connect_timeout_s = 10;
  double transfer_timeout_s = 60;  // one attempt, whole transfer
  // A transfer below low_speed_bytes_per_s for low_speed_time_s is abandoned
  // (and retried): a slow drip does not hold a connection forever.
  long low_speed_bytes_per_s = 512;
  long low_speed_time_s = 10;
  int max_retries = 4;  // attempts after the first
  double backoff_initial_s = 0.25;
  double backoff_max_s = 8;
  std::string cache_dir;  // "" = no disk cache
  uint64_t cache_max_bytes = 512ull << 20;
  bool offline = false;  // answer from the cache only
  // Where the client reports what a user should know (a broken tile, once per
  // URL; a host that asked to wait): one line, no newline. Called on the
  // client's thread. nullptr = stderr.
  std::function<void(const std::string&)> log;
};

enum class Outcome {
  kOk,         // body holds the answer (from the network or the cache)
  kNoContent,  // 404 / 410 / 204: there is no such tile
  kBroken,     // an answer that is not what was asked for (content type, validate)
  kFailed,     // no answer after the retries, or a 4xx other than 404/410/429
  kCancelled,  // cancel() or the client's destruction
  kOffline,    // offline and not in the cache
};
const char* to_string(Outcome o);

struct Response {
  Outcome outcome = Outcome::kFailed;
  int status = 0;  // the last HTTP status seen (0: none)
  std::vector<uint8_t> body;
  std::string content_type;
  std::string etag;          // as the server sent it (quotes included), "" if none
  bool from_cache = false;   // answered from the disk cache (fresh, revalidated or offline)
  bool revalidated = false;  // a 304 confirmed the cached body
  int attempts = 0;          // requests made for it (0: answered from the cache alone)
  std::string error;         // kBroken / kFailed / kOffline: what went wrong, with the URL
};

struct Request {
  std::string url;
  double priority = 0;  // higher first; ties in submission order
  // "bytes=A-B" for a Range request ("" = whole body); part of the cache key.
  std::string range;
  // Accepted Content-Type prefixes ("image/", "application/json",
  // "application/octet-stream"); empty = any. Parameters (";charset") ignored.
  std::vector<std::string> accept_types;
  // Runs on the client's thread on a 2xx body that passed accept_types:
  // returns "" if the body is good, else why not (kBroken, not cached).
  // E.g. a decode check of the tile.
  std::function<std::string(const std::vector<uint8_t>& body, const std::string& content_type)>
      validate;
  bool use_cache = true;  // false: neither read nor written (e.g. a PMTiles header check)
};

using RequestId = uint64_t;

// Totals since the client was made (monotonic; read any time from any thread).
struct ClientStats {
  uint64_t requests = 0;     // HTTP requests sent (attempts, revalidations included)
  uint64_t bytes = 0;        // body bytes received from the network
  uint64_t cache_hits = 0;   // answered from the cache (fresh, 304, or offline)
  uint64_t revalidated = 0;  // of them, after a 304
  uint64_t retries = 0;      // attempts after a first (5xx, 429, timeouts, resets)
  uint64_t no_content = 0;   // kNoContent answers (network or remembered)
  uint64_t broken = 0;       // kBroken answers
  uint64_t failed = 0;       // kFailed answers
  uint64_t cancelled = 0;    // kCancelled answers
  int in_flight = 0;         // requests submitted and not yet answered
};

class HttpClient {
 public:
  // Throws NetError if the cache folder cannot be used or libcurl cannot start.
  explicit HttpClient(ClientOptions options);
  // Cancels what is pending (each callback gets kCancelled), then joins.
  ~HttpClient();
  HttpClient(const HttpClient&) = delete;
  HttpClient& operator=(const HttpClient&) = delete;

  // Queues `request`; `done` is called exactly once, on the client's thread,
  // never after the destructor returns. Thread-safe.
  RequestId get(Request request, std::function<void(Response)> done);
  // The queued or running request gets kCancelled (a running transfer is
  // stopped); no effect once answered. Thread-safe.
  void cancel(RequestId id);
  // Moves a queued request in the queue. Thread-safe.
  void set_priority(RequestId id, double priority);
  // get() and wait for the answer (for a TileJSON or a PMTiles header).
  // Throws NetError when called from a callback (the client's thread, which
  // would wait for itself).
  Response get_blocking(Request request);

  ClientStats stats() const;
  const ClientOptions& options() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace globe::net
