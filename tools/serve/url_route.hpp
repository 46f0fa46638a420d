// What a request path asks globe-serve for (docs/serve.md "URLs"): pure
// parsing of the already percent-decoded path, no file system, no packages;
// fuzzed (tests/fuzz/fuzz_url_route.cpp). Everything the server answers is
// one of these routes; anything else is 400 or 404 before a file or package
// is touched.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace globe::serve {

struct Route {
  enum class Kind {
    kBadRequest,  // malformed: 400
    kNotFound,    // well formed, but no such thing: 404
    kIndex,       // "/"
    kViewer,      // "/view/maplibre.html", "/view/cesium.html": `file` is the page name
    kLibrary,     // "/lib/<file>": a JavaScript library file, `file` relative to the library root
    kTileJson,    // "/NAME.json"
    kPmtiles,     // "/NAME.pmtiles"
    kLayerJson,   // "/NAME/layer.json" (quantized-mesh)
    kStyleJson,   // "/NAME/style.json" (MapLibre style of a vector package)
    kTile,        // "/NAME/Z/X/Y.EXT"
    kGlyphs,      // "/fonts/FONTSTACK/START-END.pbf" (MapLibre glyph PBFs)
  } kind = Kind::kBadRequest;
  std::string name;          // package name (file stem)
  std::string file;          // kViewer, kLibrary
  std::string fontstack;     // kGlyphs: printable ASCII and spaces, no '/'
  uint32_t glyph_start = 0;  // kGlyphs: START, a multiple of 256 below 65536 (END = START + 255)
  std::string extension;     // kTile: "terrain", "png", "jpg", "webp", "pbf", "mvt", "globe"
  int z = 0;
  uint32_t x = 0, y = 0;
  std::string reason;  // why kBadRequest / kNotFound
};

inline constexpr int kMaxZoom = 30;

// Parses a decoded request path (no query string). Rejects paths that are
// not absolute, longer than 2048 bytes, hold a NUL, a backslash, an empty,
// "." or ".." segment, or characters outside printable ASCII; names must be
// [A-Za-z0-9._-]+ not starting with '.'; z, x, y decimal without sign or
// leading zeros, z <= 30 (above: kNotFound), x, y < 2^31. Under /fonts/ a
// fontstack may hold spaces ("Noto Sans Regular", as MapLibre asks for it);
// a glyph range other than START-END.pbf as above is kNotFound. (A package
// called "fonts" keeps its other routes: glyph paths have three segments.)
Route parse_route(std::string_view path);

}  // namespace globe::serve
