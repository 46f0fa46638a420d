// GNU libmicrohttpd behind plain structs (see http_server.hpp).
#include "serve/http_server.hpp"

#include <netdb.h>
#include <sys/socket.h>
#include <sys/types.h>
#include <unistd.h>

#include <microhttpd.h>

#include <algorithm>
#include <cctype>
#include <condition_variable>
#include <cstring>
#include <mutex>
#include <stdexcept>

namespace globe::serve {
namespace {

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// %HH sequences to bytes (NUL included: the router refuses what is not
// printable); a malformed sequence stays as it is. In a query, '+' is a space.
std::string percent_decode(const char* s, bool plus_is_space) {
  std::string out;
  for (size_t i = 0; s[i]; ++i) {
    const int hi = s[i] == '%' ? hex_value(s[i + 1]) : -1;
    const int lo = hi >= 0 ? hex_value(s[i + 2]) : -1;
    if (hi >= 0 && lo >= 0) {
      out += char(hi * 16 + lo);
      i += 2;
    } else {
      out += plus_is_space && s[i] == '+' ? ' ' : s[i];
    }
  }
  return out;
}

// The library would decode %HH in place and hand the path over as a C
// string, cut at a decoded %00 ("/lib/a.js%00.png" would reach the router as
// "/lib/a.js"); it is kept raw and decoded above instead.
size_t keep_escaped(void*, MHD_Connection*, char* s) {
  return std::strlen(s);
}

MHD_Result add_header(void* cls, MHD_ValueKind, const char* key, const char* value) {
  auto& headers = *static_cast<std::map<std::string, std::string>*>(cls);
  std::string name = key;
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  const std::string v = value ? value : "";
  const auto [it, fresh] = headers.emplace(name, v);
  if (!fresh) it->second += ", " + v;  // a repeated field is one list (RFC 9110 §5.3)
  return MHD_YES;
}

MHD_Result add_argument(void* cls, MHD_ValueKind, const char* key, const char* value) {
  static_cast<std::map<std::string, std::string>*>(cls)->emplace(
      percent_decode(key, true), value ? percent_decode(value, true) : std::string());
  return MHD_YES;
}

struct StreamSlice {
  StreamReader read;
  uint64_t offset = 0;
};

ssize_t read_slice(void* cls, uint64_t pos, char* buf, size_t max) {
  auto& s = *static_cast<StreamSlice*>(cls);
  const int64_t n = s.read(s.offset + pos, buf, max);
  return n > 0 ? ssize_t(n) : MHD_CONTENT_READER_END_WITH_ERROR;
}

void free_slice(void* cls) {
  delete static_cast<StreamSlice*>(cls);
}

void free_string(void* cls) {
  delete static_cast<std::string*>(cls);
}

}  // namespace

struct HttpServer::Impl {
  HttpServerOptions options;
  Handler handler;
  int socket = -1;  // the listening socket, once bound
  MHD_Daemon* daemon = nullptr;
  std::mutex mutex;
  std::condition_variable stopped_cv;
  bool stopped = false;

  // Called once a request's headers are in, then again once its body is
  // (at once, for a request without one).
  static MHD_Result access(void* cls, MHD_Connection* connection, const char* url,
                           const char* method, const char*, const char*, size_t*,
                           void** request_state) {
    auto& self = *static_cast<Impl*>(cls);
    HttpRequest in;
    HttpResponse out;
    try {
      in.method = method;
      in.path = percent_decode(url, false);
      MHD_get_connection_values(connection, MHD_HEADER_KIND, add_header, &in.headers);
      // A request without a body is answered on the second call: answered on
      // the first, the library cannot know the request is over and closes
      // the connection (no keep-alive). One with a body is answered at once,
      // unread (the server takes none; the connection is then closed).
      const bool body =
          !in.header("transfer-encoding").empty() ||
          (!in.header("content-length").empty() && in.header("content-length") != "0");
      if (!*request_state && !body) {
        *request_state = &self;
        return MHD_YES;
      }
      MHD_get_connection_values(connection, MHD_GET_ARGUMENT_KIND, add_argument, &in.query);
      out = self.handler(in);
    } catch (const std::exception& e) {
      out = HttpResponse{};
      out.status = 500;
      out.body = std::string("internal error: ") + e.what() + "\n";
    }
    MHD_Response* response = nullptr;
    if (out.status == 304) {
      // The library writes "Content-Length: 0" for an empty 304, which RFC
      // 9110 §8.6 forbids (it must be the 200's length, if sent); a response
      // of send_length bytes gets that length, and a 304 never sends a body.
      response = MHD_create_response_from_callback(
          out.send_length, 1024,
          [](void*, uint64_t, char*, size_t) -> ssize_t {
            return MHD_CONTENT_READER_END_WITH_ERROR;
          },
          nullptr, nullptr);
    } else if (out.stream) {
      auto* slice = new StreamSlice{out.stream, out.send_offset};
      response = MHD_create_response_from_callback(out.send_length, 64 * 1024, read_slice, slice,
                                                   free_slice);
      if (!response) delete slice;
    } else {
      auto* body = new std::string(std::move(out.body));
      response = MHD_create_response_from_buffer_with_free_callback_cls(body->size(), body->data(),
                                                                        free_string, body);
      if (!response) delete body;
    }
    if (!response) return MHD_NO;  // out of memory: the library drops the connection
    if (!out.content_type.empty())
      MHD_add_response_header(response, MHD_HTTP_HEADER_CONTENT_TYPE, out.content_type.c_str());
    for (const auto& [k, v] : out.headers)
      MHD_add_response_header(response, k.c_str(), v.c_str());
    const MHD_Result queued = MHD_queue_response(connection, unsigned(out.status), response);
    MHD_destroy_response(response);
    return queued;
  }
};

HttpServer::HttpServer(const HttpServerOptions& options, Handler handler)
    : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  impl_->handler = std::move(handler);
}

HttpServer::~HttpServer() {
  if (impl_->daemon) MHD_stop_daemon(impl_->daemon);
  if (impl_->socket >= 0 && !impl_->daemon) ::close(impl_->socket);
}

int HttpServer::bind() {
  const HttpServerOptions& o = impl_->options;
  const std::string where = o.bind + ":" + std::to_string(o.port);
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_PASSIVE | AI_NUMERICSERV;
  addrinfo* found = nullptr;
  if (::getaddrinfo(o.bind.c_str(), std::to_string(o.port).c_str(), &hints, &found) != 0 || !found)
    throw std::runtime_error("cannot listen on " + where +
                             ": not an address of this machine; pick another --bind");
  int fd = -1;
  for (addrinfo* a = found; a && fd < 0; a = a->ai_next) {
    fd = ::socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC, a->ai_protocol);
    if (fd < 0) continue;
    // SO_REUSEADDR (a restarted server rebinds at once) but not SO_REUSEPORT,
    // with which a second server on a busy port would share it instead of
    // failing. The backlog is the system's largest: a burst of connections
    // must not wait for SYN retries (seconds).
    const int yes = 1;
    ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    if (::bind(fd, a->ai_addr, a->ai_addrlen) != 0 || ::listen(fd, SOMAXCONN) != 0) {
      ::close(fd);
      fd = -1;
    }
  }
  ::freeaddrinfo(found);
  if (fd < 0)
    throw std::runtime_error("cannot listen on " + where +
                             " (in use, or not an address of this machine); pick another "
                             "--port or --bind");
  sockaddr_storage addr{};
  socklen_t len = sizeof addr;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  impl_->socket = fd;
  return addr.ss_family == AF_INET6 ? ntohs(reinterpret_cast<sockaddr_in6*>(&addr)->sin6_port)
                                    : ntohs(reinterpret_cast<sockaddr_in*>(&addr)->sin_port);
}

void HttpServer::run() {
  Impl& s = *impl_;
  if (s.socket < 0) throw std::logic_error("HttpServer::run before bind");
  const unsigned threads = unsigned(std::max(1, s.options.threads));
  // One polling thread per worker; requests of a connection are answered on
  // its thread. Requests and headers are bounded by the connection's memory
  // (32 KiB: 414 or 431 beyond), idle connections by the timeout.
  MHD_OptionItem options[] = {
      {MHD_OPTION_LISTEN_SOCKET, s.socket, nullptr},
      {MHD_OPTION_CONNECTION_TIMEOUT, s.options.timeout_s, nullptr},
      {MHD_OPTION_CONNECTION_MEMORY_LIMIT, 32 * 1024, nullptr},
      {MHD_OPTION_UNESCAPE_CALLBACK, reinterpret_cast<intptr_t>(&keep_escaped), nullptr},
      {threads > 1 ? MHD_OPTION_THREAD_POOL_SIZE : MHD_OPTION_END, threads, nullptr},
      {MHD_OPTION_END, 0, nullptr},
  };
  s.daemon = MHD_start_daemon(MHD_USE_INTERNAL_POLLING_THREAD | MHD_USE_EPOLL, 0, nullptr, nullptr,
                              &Impl::access, &s, MHD_OPTION_ARRAY, options, MHD_OPTION_END);
  if (!s.daemon) throw std::runtime_error("cannot start the HTTP server's threads");
  std::unique_lock lock(s.mutex);
  s.stopped_cv.wait(lock, [&] { return s.stopped; });
  lock.unlock();
  MHD_stop_daemon(s.daemon);  // closes the listening socket too
  s.daemon = nullptr;
  s.socket = -1;
}

void HttpServer::stop() {
  {
    std::lock_guard lock(impl_->mutex);
    impl_->stopped = true;
  }
  impl_->stopped_cv.notify_all();
}

}  // namespace globe::serve
