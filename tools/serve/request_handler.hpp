// Every request globe-serve answers (docs/serve.md): the route, then the
// package service, page or glyph range (web/glyphs.hpp); and what every answer carries: CORS, and
// on an answer with a body its ETag, Cache-Control, gzip for clients that accept it, 304 for
// If-None-Match, byte ranges with If-Range (http_semantics.hpp).
#pragma once

#include <memory>
#include <string>

#include "serve/http_server.hpp"
#include "serve/package_registry.hpp"
#include "web/glyphs.hpp"

namespace globe::serve {

struct HandlerOptions {
  std::string lib_dir;           // the npm packages served under /lib ("" = none)
  std::string lib_url = "/lib";  // where the preview pages load MapLibre, CesiumJS, pmtiles
  std::string fallback_host;     // host:port when a request has no usable Host header
  bool log = true;               // one line per request on stderr
  // The glyphs of the styles' labels under /fonts (nullptr: none, 404).
  std::shared_ptr<const web::GlyphSet> glyphs;
};

class RequestHandler {
 public:
  RequestHandler(PackageRegistry& registry, HandlerOptions options);
  HttpResponse operator()(const HttpRequest& request);
  // Set once the port is known, before the first request.
  void set_fallback_host(const std::string& host) { options_.fallback_host = host; }

 private:
  HttpResponse route(const HttpRequest& request);
  HttpResponse library_file(const std::string& file);
  HttpResponse glyph_range(const Route& route);
  static void finish(const HttpRequest& request, HttpResponse& answer);

  PackageRegistry& registry_;
  HandlerOptions options_;
  std::string lib_root_;  // canonical lib_dir
};

}  // namespace globe::serve
