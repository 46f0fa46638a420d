// Requests to answers (see request_handler.hpp).
#include "serve/request_handler.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <span>

#include "serve/preview_pages.hpp"
#include "serve/url_route.hpp"
#include "tileformat/fnv1a.hpp"
#include "web/gzip.hpp"

namespace globe::serve {
namespace {

namespace fs = std::filesystem;

const char* content_type_of(const fs::path& file) {
  const std::string ext = file.extension().string();
  if (ext == ".js" || ext == ".mjs" || ext == ".cjs") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".json" || ext == ".map") return "application/json";
  if (ext == ".png") return "image/png";
  if (ext == ".jpg" || ext == ".jpeg") return "image/jpeg";
  if (ext == ".svg") return "image/svg+xml";
  if (ext == ".wasm") return "application/wasm";
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".xml") return "application/xml";
  if (ext == ".glb") return "model/gltf-binary";
  return "application/octet-stream";
}

// The Host header if it is a plain host[:port], else the fallback.
std::string host_of(const HttpRequest& req, const std::string& fallback) {
  const std::string h = req.header("host");
  if (h.empty() || h.size() > 255) return fallback;
  for (char c : h)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == ':' ||
          c == '[' || c == ']'))
      return fallback;
  return h;
}

// Whether a Range header can be satisfied from `size` bytes (RFC 9110
// 14.1.2: some range starts before the end, or a suffix range is not
// empty). The HTTP library slices the body but, for bodies read on demand,
// does not refuse ranges past the end.
bool satisfiable(const std::string& range, uint64_t size) {
  if (range.rfind("bytes=", 0) != 0) return true;  // not a byte range: ignored
  size_t at = 6;
  while (at <= range.size()) {
    const size_t comma = range.find(',', at);
    std::string part =
        range.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
    part.erase(0, part.find_first_not_of(' '));
    const size_t dash = part.find('-');
    if (dash != std::string::npos) {
      const std::string first = part.substr(0, dash), last = part.substr(dash + 1);
      const bool digits = first.find_first_not_of("0123456789") == std::string::npos &&
                          last.find_first_not_of("0123456789") == std::string::npos &&
                          first.size() <= 19 && last.size() <= 19;
      if (digits && first.empty() && !last.empty() && std::stoull(last) > 0 && size > 0)
        return true;
      if (digits && !first.empty() && std::stoull(first) < size) return true;
    }
    if (comma == std::string::npos) break;
    at = comma + 1;
  }
  return false;
}

}  // namespace

RequestHandler::RequestHandler(PackageRegistry& registry, HandlerOptions options)
    : registry_(registry), options_(std::move(options)) {
  std::error_code ec;
  if (!options_.lib_dir.empty()) lib_root_ = fs::canonical(options_.lib_dir, ec).string();
  if (ec) lib_root_.clear();
}

HttpResponse RequestHandler::library_file(const std::string& file) {
  if (lib_root_.empty())
    return text_response(404, "no JavaScript libraries here (globe-serve --web-libs DIR)");
  // Resolved with symlinks; must stay under the library root.
  std::error_code ec;
  const fs::path path = fs::weakly_canonical(fs::path(lib_root_) / file, ec);
  const std::string p = path.string();
  if (ec || p.size() <= lib_root_.size() || p.compare(0, lib_root_.size(), lib_root_) != 0 ||
      p[lib_root_.size()] != '/')
    return text_response(404, "no such library file");
  if (!fs::is_regular_file(path, ec)) return text_response(404, "no such library file");
  const uint64_t size = fs::file_size(path, ec);
  if (ec || size > (uint64_t{256} << 20)) return text_response(404, "no such library file");
  HttpResponse out;
  out.content_type = content_type_of(path);
  out.stream_size = size;
  out.headers.push_back({"Cache-Control", "public, max-age=86400"});
  out.stream = [p](uint64_t offset, uint64_t length, std::string& chunk) {
    const int fd = ::open(p.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return false;
    chunk.resize(length);
    const ssize_t n = ::pread(fd, chunk.data(), length, off_t(offset));
    ::close(fd);
    if (n <= 0) return false;
    chunk.resize(size_t(n));
    return true;
  };
  return out;
}

HttpResponse RequestHandler::route(const HttpRequest& req) {
  const Route r = parse_route(req.path);
  const std::string host = host_of(req, options_.fallback_host);
  switch (r.kind) {
    case Route::Kind::kBadRequest:
      return text_response(400, "bad request: " + r.reason);
    case Route::Kind::kNotFound:
      return text_response(404, "not found: " + r.reason);
    case Route::Kind::kIndex: {
      HttpResponse out;
      out.content_type = "text/html; charset=utf-8";
      out.body = index_page(registry_.list());
      out.compressible = true;
      return out;
    }
    case Route::Kind::kViewer: {
      HttpResponse out;
      out.content_type = "text/html; charset=utf-8";
      out.body =
          r.file == "cesium.html" ? cesium_page(options_.lib_url) : maplibre_page(options_.lib_url);
      out.compressible = true;
      return out;
    }
    case Route::Kind::kLibrary:
      return library_file(r.file);
    default:
      break;
  }
  const PackageRegistry::Found found = registry_.find(r.name);
  if (!found.service) return text_response(found.status, found.error);
  const std::string base = "http://" + host + "/" + r.name;
  if (r.kind == Route::Kind::kTileJson) return found.service->tilejson(base, req);
  return found.service->answer(r, req, base);
}

HttpResponse RequestHandler::operator()(const HttpRequest& req) {
  const auto start = std::chrono::steady_clock::now();
  HttpResponse out;
  if (req.method == "OPTIONS") {
    out = text_response(204, "");
    out.headers.push_back({"Access-Control-Allow-Methods", "GET, HEAD, OPTIONS"});
    out.headers.push_back(
        {"Access-Control-Allow-Headers", "Range, Accept, Accept-Encoding, If-None-Match"});
  } else if (req.method != "GET" && req.method != "HEAD") {
    out = text_response(405, req.method + " is not served; GET and HEAD are");
    out.headers.push_back({"Allow", "GET, HEAD, OPTIONS"});
  } else {
    out = route(req);
  }
  if (out.stream && !req.header("range").empty() &&
      !satisfiable(req.header("range"), out.stream_size)) {
    const uint64_t size = out.stream_size;
    out = text_response(416, "");
    out.headers.push_back({"Content-Range", "bytes */" + std::to_string(size)});
  }
  out.headers.push_back({"Access-Control-Allow-Origin", "*"});
  out.headers.push_back({"Access-Control-Expose-Headers", "ETag, Content-Range, Content-Length"});
  if (out.status == 200 && !out.stream && !out.body.empty()) {
    const bool gzip =
        out.compressible && req.header("accept-encoding").find("gzip") != std::string::npos;
    const std::span<const uint8_t> bytes(reinterpret_cast<const uint8_t*>(out.body.data()),
                                         out.body.size());
    char tag[40];
    std::snprintf(tag, sizeof tag, "\"%016llx%s\"",
                  static_cast<unsigned long long>(tileformat::fnv1a(bytes)), gzip ? "-gz" : "");
    out.headers.push_back({"ETag", tag});
    bool has_cache_control = false;
    for (const auto& [k, v] : out.headers)
      has_cache_control = has_cache_control || k == "Cache-Control";
    if (!has_cache_control) out.headers.push_back({"Cache-Control", "public, max-age=60"});
    if (out.compressible) out.headers.push_back({"Vary", "Accept-Encoding"});
    if (req.header("if-none-match") == tag) {
      out.status = 304;
      out.body.clear();
    } else if (gzip) {
      const std::vector<uint8_t> z = web::gzip(bytes, 6);
      out.body.assign(z.begin(), z.end());
      out.headers.push_back({"Content-Encoding", "gzip"});
    }
  }
  if (options_.log) {
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "%s %s %d %zu %.1f ms\n", req.method.c_str(), req.path.c_str(), out.status,
                 out.stream ? size_t(out.stream_size) : out.body.size(), ms);
  }
  return out;
}

}  // namespace globe::serve
