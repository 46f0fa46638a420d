// Requests to answers (see request_handler.hpp).
#include "serve/request_handler.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <span>

#include "serve/file_body.hpp"
#include "serve/http_semantics.hpp"
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

// /NAME/{z}/{x}/{y}.globe: the blob as the package stores it (zstd inside:
// not gzipped again); 404 where there is none.
HttpResponse native_tile(NativeTiles* native, const Route& r) {
  if (!native) return text_response(404, r.name + " has no native tiles (a .pmtiles file)");
  std::optional<std::vector<uint8_t>> blob;
  try {
    blob = native->tile({r.z, r.x, r.y});
  } catch (const std::exception& e) {
    return text_response(503, r.name + ": " + e.what());
  }
  if (!blob)
    return text_response(404, "no tile " + std::to_string(r.z) + "/" + std::to_string(r.x) + "/" +
                                  std::to_string(r.y));
  HttpResponse out;
  out.content_type = "application/vnd.globe.tile";
  out.body.assign(blob->begin(), blob->end());
  return out;
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
  const std::shared_ptr<const OpenFile> f = OpenFile::open(path.string());
  if (!f || f->size() > (uint64_t{256} << 20)) return text_response(404, "no such library file");
  HttpResponse out = file_response(f, content_type_of(path));
  out.headers.push_back({"Cache-Control", "public, max-age=86400"});
  return out;
}

// A glyph range of the styles' fontstack, made on first ask and kept
// (web::GlyphSet): cacheable for a day, as the libraries are.
HttpResponse RequestHandler::glyph_range(const Route& r) {
  if (!options_.glyphs)
    return text_response(404, "no glyphs here: globe-serve found no fonts (fonts-noto-core)");
  if (r.fontstack != options_.glyphs->fontstack())
    return text_response(404, "no fontstack '" + r.fontstack + "'; the styles' is '" +
                                  options_.glyphs->fontstack() + "'");
  const std::shared_ptr<const std::string> pbf = options_.glyphs->range(r.glyph_start);
  if (!pbf) return text_response(404, "no glyphs in this range");
  HttpResponse out;
  out.content_type = "application/x-protobuf";
  out.body = *pbf;
  out.compressible = true;
  out.headers.push_back({"Cache-Control", "public, max-age=86400"});
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
      const auto packages = registry_.list();
      out.body = r.file == "cesium.html" ? cesium_page(options_.lib_url, packages)
                                         : maplibre_page(options_.lib_url, packages);
      out.compressible = true;
      return out;
    }
    case Route::Kind::kLibrary:
      return library_file(r.file);
    case Route::Kind::kGlyphs:
      return glyph_range(r);
    default:
      break;
  }
  const PackageRegistry::Found found = registry_.find(r.name);
  if (!found.service) return text_response(found.status, found.error);
  const std::string base = "http://" + host + "/" + r.name;
  NativeTiles* native = found.service->native.get();
  if (r.kind == Route::Kind::kTileJson) {
    HttpResponse out = found.service->tilejson(base, req);
    if (native && out.status == 200)
      out.body = with_member(out.body, native->tilejson_member(base));
    return out;
  }
  if (r.kind == Route::Kind::kTile && r.extension == "globe") return native_tile(native, r);
  return found.service->answer(r, req, base);
}

namespace {

bool has_header(const HttpResponse& r, const char* name) {
  for (const auto& [k, v] : r.headers)
    if (k == name) return true;
  return false;
}

// The bytes [first, last] of the answer's body, streamed or in memory.
bool body_slice(const HttpResponse& r, const http::ByteRange& range, std::string& out) {
  if (!r.stream) {
    out = r.body.substr(size_t(range.first), size_t(range.length()));
    return true;
  }
  out.resize(size_t(range.length()));
  for (uint64_t got = 0; got < range.length();) {
    const int64_t n = r.stream(range.first + got, out.data() + got, range.length() - got);
    if (n <= 0) return false;
    got += uint64_t(n);
  }
  return true;
}

// Multipart answers are assembled in memory; past this a file's ranges are
// answered with the whole file instead (RFC 9110 §14.2 allows ignoring Range).
constexpr uint64_t kMultipartBytes = uint64_t{16} << 20;

}  // namespace

// RFC 9110 on a 200 answer with a body (docs/serve.md "HTTP"): the
// representation (gzip or not), its validators and caching, then
// If-None-Match (304), then Range with If-Range (206, multipart, 416). Only
// GET takes ranges; HEAD gets GET's headers (the library drops the body).
void RequestHandler::finish(const HttpRequest& req, HttpResponse& out) {
  const bool gzip =
      out.compressible && !out.stream && http::accepts_gzip(req.header("accept-encoding"));
  if (!out.stream) {
    const std::span<const uint8_t> bytes(reinterpret_cast<const uint8_t*>(out.body.data()),
                                         out.body.size());
    char tag[40];
    std::snprintf(tag, sizeof tag, "\"%016llx%s\"",
                  static_cast<unsigned long long>(tileformat::fnv1a(bytes)), gzip ? "-gz" : "");
    out.etag = tag;
  }
  if (!out.etag.empty()) out.headers.push_back({"ETag", out.etag});
  if (!has_header(out, "Cache-Control"))
    out.headers.push_back({"Cache-Control", "public, max-age=60"});
  if (out.compressible) out.headers.push_back({"Vary", "Accept-Encoding"});
  if (gzip) {
    const std::vector<uint8_t> z =
        web::gzip({reinterpret_cast<const uint8_t*>(out.body.data()), out.body.size()}, 6);
    out.body.assign(z.begin(), z.end());
    out.headers.push_back({"Content-Encoding", "gzip"});
  }
  if (http::none_match_fails(req.header("if-none-match"), out.etag)) {
    // 304: the validators and caching fields (RFC 9110 §15.4.5), no body;
    // its Content-Length, if any, must be what the 200 would send (§8.6):
    // the HTTP layer writes send_length there.
    std::vector<std::pair<std::string, std::string>> kept;
    for (auto& h : out.headers)
      if (h.first == "ETag" || h.first == "Cache-Control" || h.first == "Vary")
        kept.push_back(std::move(h));
    out.status = 304;
    out.send_length = out.stream ? out.stream_size : out.body.size();
    out.headers = std::move(kept);
    out.body.clear();
    out.stream = nullptr;
    out.content_type.clear();
    return;
  }
  if (!out.last_modified.empty()) out.headers.push_back({"Last-Modified", out.last_modified});
  out.headers.push_back({"Accept-Ranges", "bytes"});
  const std::string range = req.header("range");
  if (req.method != "GET" || range.empty() ||
      !http::if_range_holds(req.header("if-range"), out.etag, out.last_modified))
    return;
  const uint64_t size = out.stream ? out.stream_size : out.body.size();
  const http::RangeRequest r = http::parse_range(range, size);
  if (r.kind == http::RangeRequest::Kind::kWhole) return;
  if (r.kind == http::RangeRequest::Kind::kUnsatisfiable) {
    HttpResponse refused = text_response(
        416, "range not satisfiable: the body has " + std::to_string(size) + " bytes");
    refused.headers = {{"Content-Range", http::unsatisfied_range(size)}, {"ETag", out.etag}};
    out = std::move(refused);
    return;
  }
  if (r.ranges.size() == 1) {
    const http::ByteRange& one = r.ranges.front();
    out.status = 206;
    out.headers.push_back({"Content-Range", http::content_range(one, size)});
    if (out.stream) {
      out.send_offset = one.first;
      out.send_length = one.length();
    } else {
      out.body = out.body.substr(size_t(one.first), size_t(one.length()));
    }
    return;
  }
  uint64_t total = 0;
  for (const http::ByteRange& b : r.ranges)
    total += b.length();
  if (total > kMultipartBytes) return;
  std::vector<std::string> parts(r.ranges.size());
  for (size_t i = 0; i < parts.size(); ++i)
    if (!body_slice(out, r.ranges[i], parts[i])) {
      out = text_response(500, "cannot read the file");
      return;
    }
  std::string boundary;
  std::string body = http::multipart_byteranges(r.ranges, parts, size, out.content_type, boundary);
  out.status = 206;
  out.stream = nullptr;
  out.body = std::move(body);
  out.content_type = "multipart/byteranges; boundary=" + boundary;
}

HttpResponse RequestHandler::operator()(const HttpRequest& req) {
  const auto start = std::chrono::steady_clock::now();
  HttpResponse out;
  if (req.method == "OPTIONS") {
    out = text_response(204, "");
    out.headers.push_back({"Access-Control-Allow-Methods", "GET, HEAD, OPTIONS"});
    out.headers.push_back({"Access-Control-Allow-Headers",
                           "Range, Accept, Accept-Encoding, If-None-Match, If-Range"});
  } else if (req.method != "GET" && req.method != "HEAD") {
    out = text_response(405, req.method + " is not served; GET and HEAD are");
    out.headers.push_back({"Allow", "GET, HEAD, OPTIONS"});
  } else {
    out = route(req);
  }
  if (out.status == 200 && (out.stream || !out.body.empty())) finish(req, out);
  if (out.status == 204) out.content_type.clear();
  out.headers.push_back({"Access-Control-Allow-Origin", "*"});
  out.headers.push_back(
      {"Access-Control-Expose-Headers", "ETag, Content-Range, Content-Length, Accept-Ranges"});
  if (options_.log) {
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(
        stderr, "%s %s %d %llu %.1f ms\n", req.method.c_str(), req.path.c_str(), out.status,
        static_cast<unsigned long long>(out.stream ? out.send_length : out.body.size()), ms);
  }
  return out;
}

}  // namespace globe::serve
