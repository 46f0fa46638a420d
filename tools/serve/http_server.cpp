// cpp-httplib behind plain structs (see http_server.hpp).
#include "serve/http_server.hpp"

#include <httplib.h>
#include <sys/socket.h>

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace globe::serve {

struct HttpServer::Impl {
  HttpServerOptions options;
  int socket = -1;  // the listening socket, once bound
  Handler handler;
  httplib::Server server;
};

HttpServer::HttpServer(const HttpServerOptions& options, Handler handler)
    : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  impl_->handler = std::move(handler);
  httplib::Server& s = impl_->server;
  const int threads = std::max(1, options.threads);
  s.new_task_queue = [threads] { return new httplib::ThreadPool(size_t(threads)); };
  s.set_read_timeout(options.timeout_s, 0);
  s.set_write_timeout(options.timeout_s, 0);
  s.set_keep_alive_timeout(std::min(options.timeout_s, 5));
  // Headers and body go out in separate writes: without TCP_NODELAY, Nagle's
  // algorithm and the client's delayed ACK cost 40 ms per kept-alive request.
  s.set_tcp_nodelay(true);
  s.set_keep_alive_max_count(100);
  s.set_payload_max_length(64 * 1024);  // requests carry no body worth reading
  // SO_REUSEADDR but not the library's default SO_REUSEPORT, with which a
  // second server on a busy port would share it instead of failing.
  s.set_socket_options([this](socket_t sock) {
    int yes = 1;
    ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    impl_->socket = sock;
  });
  s.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    HttpRequest in;
    in.method = req.method;
    in.path = req.path;
    for (const auto& [k, v] : req.params)
      in.query.emplace(k, v);
    for (const auto& [k, v] : req.headers) {
      std::string lower = k;
      std::transform(lower.begin(), lower.end(), lower.begin(),
                     [](unsigned char c) { return char(std::tolower(c)); });
      in.headers.emplace(lower, v);
    }
    HttpResponse out;
    try {
      out = impl_->handler(in);
    } catch (const std::exception& e) {
      out = HttpResponse{};
      out.status = 500;
      out.body = std::string("internal error: ") + e.what() + "\n";
    }
    // 200 is left to the library, which makes it 206 for a range request.
    if (out.status != 200) res.status = out.status;
    for (const auto& [k, v] : out.headers)
      res.set_header(k, v);
    if (out.stream) {
      auto stream = out.stream;
      res.set_content_provider(size_t(out.stream_size), out.content_type,
                               [stream](size_t offset, size_t length, httplib::DataSink& sink) {
                                 std::string chunk;
                                 const size_t piece = std::min<size_t>(length, 1 << 20);
                                 if (!stream(offset, piece, chunk)) return false;
                                 return sink.write(chunk.data(), chunk.size());
                               });
    } else if (!out.body.empty() || out.status != 204) {
      res.set_content(out.body, out.content_type);
    }
    return httplib::Server::HandlerResponse::Handled;
  });
}

HttpServer::~HttpServer() = default;

int HttpServer::bind() {
  const HttpServerOptions& o = impl_->options;
  int port = o.port;
  if (o.port == 0) {
    port = impl_->server.bind_to_any_port(o.bind.c_str());
  } else if (!impl_->server.bind_to_port(o.bind.c_str(), o.port)) {
    port = -1;
  }
  // The library listens with a backlog of 5: under a burst of connections
  // the rest would wait for SYN retries (seconds). Listening again only
  // raises the backlog.
  if (port >= 0 && impl_->socket >= 0) ::listen(impl_->socket, SOMAXCONN);
  if (port < 0)
    throw std::runtime_error("cannot listen on " + o.bind + ":" + std::to_string(o.port) +
                             " (in use, or not an address of this machine); pick another "
                             "--port or --bind");
  return port;
}

void HttpServer::run() {
  impl_->server.listen_after_bind();
}

void HttpServer::stop() {
  impl_->server.stop();
}

}  // namespace globe::serve
