// CurlMulti: lib/net's one wrapper of libcurl. A multi handle with its
// connection caps, one easy handle per transfer (HTTP/2 where offered, gzip,
// timeouts, the low-speed limit), the response's headers collected as they
// come, and each finished transfer classified: done (any HTTP status),
// retryable (timeouts, resets, truncated bodies) or not. Knows nothing of
// queues, retries or caching: HttpClient (http_client.cpp) decides.
// Used from one thread, but wakeup(), which any thread may call.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace globe::net::detail {

struct CurlSettings {
  std::string user_agent;
  long max_host_connections = 6;
  long max_total_connections = 24;
  double connect_timeout_s = 10;
  double transfer_timeout_s = 60;
  long low_speed_bytes_per_s = 512;
  long low_speed_time_s = 10;
};

struct TransferSpec {
  std::string url;
  std::vector<std::string> headers;  // "Name: value" lines (Range, If-None-Match, ...)
  // Ask for gzip / deflate (CURLOPT_ACCEPT_ENCODING ""); off for ranges,
  // whose byte offsets are those of the unencoded body.
  bool compressed = true;
};

enum class TransferFailure {
  kNone,       // an HTTP answer came whole (any status)
  kRetryable,  // timeout, reset, refused connection, truncated body, slow drip
  kPermanent,  // a bad URL, an unsupported protocol, a certificate that fails
};

struct TransferResult {
  uint64_t token = 0;
  TransferFailure failure = TransferFailure::kNone;
  std::string error;  // what went wrong, in curl's words (failure != kNone)
  int status = 0;     // the last response's HTTP status (0: none)
  std::vector<uint8_t> body;
  // The last response's headers, names in lower case; a repeated header's
  // values joined with ", ".
  std::map<std::string, std::string> headers;
  uint64_t bytes_received = 0;  // body bytes off the wire (before decoding)

  std::string header(const std::string& lower_case_name) const {
    const auto it = headers.find(lower_case_name);
    return it == headers.end() ? std::string() : it->second;
  }
};

class CurlMulti {
 public:
  // Throws NetError if libcurl cannot start.
  explicit CurlMulti(const CurlSettings& settings);
  ~CurlMulti();
  CurlMulti(const CurlMulti&) = delete;
  CurlMulti& operator=(const CurlMulti&) = delete;

  // Starts a transfer; its result comes from a later perform() with `token`.
  // Throws NetError if libcurl refuses it.
  void start(uint64_t token, const TransferSpec& spec);
  // Stops a running transfer; no result will come for it. No effect on an
  // unknown token.
  void abort(uint64_t token);
  // Moves the transfers on; returns those that finished.
  std::vector<TransferResult> perform();
  // Sleeps until a socket is ready, libcurl's own timeout, wakeup() or
  // timeout_ms, whichever comes first.
  void wait(int timeout_ms);
  // Ends a wait() now or the next one at once. Thread-safe.
  void wakeup();
  size_t running() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace globe::net::detail
