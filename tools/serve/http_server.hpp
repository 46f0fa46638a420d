// The one wrapper of GNU libmicrohttpd (Debian's libmicrohttpd-dev): an
// HTTP/1.1 server on one address and port, a pool of worker threads each
// polling its share of the connections (epoll), every request (any method,
// any path) handed to one handler as plain structs. The library moves bytes
// only: it parses requests, bounds their size and time, keeps connections
// alive, drops the body of HEAD answers and writes Content-Length. What the
// answer means — ranges, conditionals, gzip, ETags — is the handler's
// (request_handler.cpp with http_semantics.hpp), so it is written once and
// tested without a network (docs/serve.md "HTTP" says why this library).
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
  std::map<std::string, std::string> headers;  // names in lower case; repeats joined by ", "
  std::string header(const std::string& lower_name) const {
    const auto it = headers.find(lower_name);
    return it == headers.end() ? std::string() : it->second;
  }
};

// Reads up to `length` bytes at `offset` into `out`; the count read (0 at the
// end), or -1 on an error.
using StreamReader = std::function<int64_t(uint64_t offset, char* out, uint64_t length)>;

struct HttpResponse {
  int status = 200;
  std::string content_type = "text/plain; charset=utf-8";
  std::string body;
  std::vector<std::pair<std::string, std::string>> headers;
  bool compressible = false;  // gzip it for clients that accept gzip
  // A body read on demand (a file) instead of `body`: the representation's
  // size and its reader; the bytes sent are [send_offset, send_offset +
  // send_length) (the whole file until a range says otherwise).
  uint64_t stream_size = 0;
  StreamReader stream;
  uint64_t send_offset = 0, send_length = 0;
  // Validators of a streamed file, from its identity (size, time), set by
  // whoever opened it; in-memory bodies get an ETag from their bytes.
  std::string etag, last_modified;
};

struct HttpServerOptions {
  std::string bind = "127.0.0.1";
  int port = 8080;  // 0: any free port
  // Worker threads, each polling its share of the connections: they bound
  // the requests worked on at once (and their memory), not the connections.
  int threads = 2;
  int timeout_s = 10;  // a connection idle this long (mid-request too) is closed
};

class HttpServer {
 public:
  using Handler = std::function<HttpResponse(const HttpRequest&)>;
  HttpServer(const HttpServerOptions& options, Handler handler);
  ~HttpServer();
  // Binds and listens; returns the port. Throws std::runtime_error naming the
  // address when it cannot.
  int bind();
  // Serves until stop() (from another thread or a signal handler's thread).
  void run();
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace globe::serve
