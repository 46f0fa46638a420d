// Request paths to routes (see url_route.hpp).
#include "serve/url_route.hpp"

#include <vector>

namespace globe::serve {
namespace {

Route bad(std::string reason) {
  Route r;
  r.kind = Route::Kind::kBadRequest;
  r.reason = std::move(reason);
  return r;
}

Route not_found(std::string reason) {
  Route r;
  r.kind = Route::Kind::kNotFound;
  r.reason = std::move(reason);
  return r;
}

bool is_name(std::string_view s) {
  if (s.empty() || s.size() > 200 || s[0] == '.') return false;
  for (char c : s)
    if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' ||
          c == '_' || c == '-'))
      return false;
  return true;
}

// Decimal without sign or leading zeros, below `limit`.
bool number(std::string_view s, uint64_t limit, uint64_t& out) {
  if (s.empty() || s.size() > 10 || (s.size() > 1 && s[0] == '0')) return false;
  out = 0;
  for (char c : s) {
    if (c < '0' || c > '9') return false;
    out = out * 10 + uint64_t(c - '0');
  }
  return out < limit;
}

bool ends_with(std::string_view s, std::string_view tail) {
  return s.size() >= tail.size() && s.substr(s.size() - tail.size()) == tail;
}

// "/fonts/FONTSTACK/START-END.pbf": START a multiple of 256 in the Basic
// Multilingual Plane (what MapLibre GL asks for), END = START + 255.
Route glyph_route(std::string_view fontstack, std::string_view file) {
  if (fontstack.size() > 200 || fontstack.front() == ' ' || fontstack.back() == ' ')
    return not_found("no such fontstack");
  if (!ends_with(file, ".pbf")) return not_found("a glyph range is START-END.pbf");
  const std::string_view range = file.substr(0, file.size() - 4);
  const size_t dash = range.find('-');
  uint64_t start = 0, end = 0;
  if (dash == std::string_view::npos || !number(range.substr(0, dash), 65536, start) ||
      !number(range.substr(dash + 1), 65536, end) || start % 256 != 0 || end != start + 255)
    return not_found(
        "a glyph range is START-END.pbf, START a multiple of 256 below 65536 and "
        "END = START + 255");
  Route r;
  r.kind = Route::Kind::kGlyphs;
  r.fontstack = std::string(fontstack);
  r.glyph_start = uint32_t(start);
  return r;
}

}  // namespace

Route parse_route(std::string_view path) {
  if (path.empty() || path[0] != '/') return bad("the path must start with /");
  if (path.size() > 2048) return bad("the path is longer than 2048 bytes");
  // Fontstacks are font names with spaces ("Noto Sans Regular"); nothing else has one.
  const bool fonts = path.starts_with("/fonts/");
  for (char c : path)
    if (c == '\0' || c == '\\' || static_cast<unsigned char>(c) < (fonts ? 0x20 : 0x21) ||
        static_cast<unsigned char>(c) > 0x7e)
      return bad("the path holds a character that is not printable ASCII or is a backslash");
  Route r;
  if (path == "/") {
    r.kind = Route::Kind::kIndex;
    return r;
  }
  std::vector<std::string_view> parts;
  for (size_t at = 1;;) {
    const size_t slash = path.find('/', at);
    const std::string_view part =
        path.substr(at, slash == std::string_view::npos ? std::string_view::npos : slash - at);
    if (part.empty() || part == "." || part == "..")
      return bad("the path has an empty, '.' or '..' segment");
    parts.push_back(part);
    if (slash == std::string_view::npos) break;
    at = slash + 1;
  }
  if (parts[0] == "lib") {
    if (parts.size() < 2) return not_found("/lib/ alone is not a file");
    for (std::string_view p : parts)
      if (p[0] == '.') return bad("library paths have no hidden segments");
    r.kind = Route::Kind::kLibrary;
    r.file = std::string(path.substr(5));
    return r;
  }
  if (fonts && parts.size() == 3) return glyph_route(parts[1], parts[2]);
  if (fonts && path.find(' ') != std::string_view::npos)
    return not_found("glyphs are /fonts/FONTSTACK/START-END.pbf");
  if (parts[0] == "view") {
    if (parts.size() != 2 || (parts[1] != "maplibre.html" && parts[1] != "cesium.html"))
      return not_found("the viewers are /view/maplibre.html and /view/cesium.html");
    r.kind = Route::Kind::kViewer;
    r.file = std::string(parts[1]);
    return r;
  }
  if (parts.size() == 1) {
    const std::string_view p = parts[0];
    for (const auto& [tail, kind] :
         {std::pair{std::string_view(".json"), Route::Kind::kTileJson},
          std::pair{std::string_view(".pmtiles"), Route::Kind::kPmtiles}})
      if (ends_with(p, tail)) {
        const std::string_view name = p.substr(0, p.size() - tail.size());
        if (!is_name(name)) return bad("'" + std::string(name) + "' is not a package name");
        r.kind = kind;
        r.name = std::string(name);
        return r;
      }
    return not_found("no such file");
  }
  if (!is_name(parts[0])) return bad("'" + std::string(parts[0]) + "' is not a package name");
  r.name = std::string(parts[0]);
  if (parts.size() == 2) {
    if (parts[1] == "layer.json") {
      r.kind = Route::Kind::kLayerJson;
      return r;
    }
    if (parts[1] == "style.json") {
      r.kind = Route::Kind::kStyleJson;
      return r;
    }
    return not_found("a package has layer.json, style.json and tiles Z/X/Y.EXT");
  }
  if (parts.size() != 4) return bad("a tile path is /NAME/Z/X/Y.EXT");
  const size_t dot = parts[3].find('.');
  if (dot == std::string_view::npos) return bad("a tile path ends in Y.EXT");
  r.extension = std::string(parts[3].substr(dot + 1));
  if (r.extension != "terrain" && r.extension != "png" && r.extension != "jpg" &&
      r.extension != "webp" && r.extension != "pbf" && r.extension != "mvt" &&
      r.extension != "globe")
    return bad("tile extensions are terrain, png, jpg, webp, pbf and mvt");
  uint64_t z, x, y;
  if (!number(parts[1], uint64_t{1} << 31, z) || !number(parts[2], uint64_t{1} << 31, x) ||
      !number(parts[3].substr(0, dot), uint64_t{1} << 31, y))
    return bad("Z, X and Y are decimal numbers without sign or leading zeros");
  if (z > uint64_t(kMaxZoom)) return not_found("zoom " + std::to_string(z) + " is beyond 30");
  r.kind = Route::Kind::kTile;
  r.z = int(z), r.x = uint32_t(x), r.y = uint32_t(y);
  return r;
}

}  // namespace globe::serve
