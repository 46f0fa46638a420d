// The one wrapper of cpp-httplib (Debian's libcpp-httplib-dev): an HTTP/1.1
// server on one address and port, a pool of worker threads, every request
// (any method, any path) handed to one handler as plain structs. Byte ranges
// (206, 416) are applied by the library to whatever the handler answers;
// read and write timeouts bound slow clients; the library bounds the request
// line and each header to 8 KiB.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace globe::serve {

struct HttpRequest {
  std::string method;                          // "GET", "HEAD", ...
  std::string path;                            // percent-decoded, no query
  std::map<std::string, std::string> query;    // decoded parameters
  std::map<std::string, std::string> headers;  // names in lower case
  std::string header(const std::string& lower_name) const {
    const auto it = headers.find(lower_name);
    return it == headers.end() ? std::string() : it->second;
  }
};

struct HttpResponse {
  int status = 200;
  std::string content_type = "text/plain; charset=utf-8";
  std::string body;
  std::vector<std::pair<std::string, std::string>> headers;
  bool compressible = false;  // gzip it for clients that accept gzip
  // A body read on demand (a large file): its size and a reader of
  // [offset, offset + length) into `out`; returns false on a read error.
  uint64_t stream_size = 0;
  std::function<bool(uint64_t offset, uint64_t length, std::string& out)> stream;
};

struct HttpServerOptions {
  std::string bind = "127.0.0.1";
  int port = 8080;  // 0: any free port
  // The library gives each connection a thread for its whole keep-alive
  // life: threads bound the connections served at once, not the cores used.
  int threads = 64;
  int timeout_s = 10;  // read and write timeouts
};

class HttpServer {
 public:
  using Handler = std::function<HttpResponse(const HttpRequest&)>;
  HttpServer(const HttpServerOptions& options, Handler handler);
  ~HttpServer();
  // Binds; returns the port. Throws std::runtime_error naming the address
  // when it cannot.
  int bind();
  // Serves until stop() (from another thread or a signal handler's thread).
  void run();
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace globe::serve
