// What globe-serve answers for one package (docs/serve.md): one service per
// package kind, each answering its routes from the package opened read-only.
// Terrain: quantized-mesh (layer.json, .terrain, TMS rows) and raster-DEM PNG
// (?encoding=terrarium|terrain-rgb) cut on the fly; images: tiles as stored;
// lines, bundles, points and areas: MVT (with the labels' names), a MapLibre
// style (their symbol layers reading /fonts) and the tiles drawn as PNG images; a .pmtiles file:
// its bytes (ranges applied by the HTTP layer). Every service is safe to call from several threads.
#pragma once

#include <memory>
#include <string>

#include "serve/http_server.hpp"
#include "serve/native_tiles.hpp"
#include "serve/url_route.hpp"

namespace globe::serve {

// Where a tile set lies: lon/lat bounds and zooms (TileJSON, the preview).
struct TileSetExtent {
  double west = -180, south = -85, east = 180, north = 85;
  int min_zoom = 0, max_zoom = 0;
};

class PackageService : public TileSetExtent {
 public:
  virtual ~PackageService() = default;
  // "terrain", "images", "lines", "points", "areas", "pmtiles".
  virtual std::string kind() const = 0;
  // "webmercator", "geodetic", "local"; "" for a .pmtiles file.
  virtual std::string tiling() const = 0;
  // TileJSON 3.0.0 with tile URLs under `base` (http://host:port/NAME); the
  // request's query may choose among a kind's tile sets (terrain: ?encoding=
  // gives the raster-DEM PNGs').
  virtual HttpResponse tilejson(const std::string& base, const HttpRequest& request) = 0;
  // The package's own tiles and metadata as stored, for globe-view's remote
  // sources; null for a .pmtiles file. Set by open_service.
  std::unique_ptr<NativeTiles> native;
  // kTile, kLayerJson, kStyleJson, kPmtiles; 404 for routes the kind lacks.
  virtual HttpResponse answer(const Route& route, const HttpRequest& request,
                              const std::string& base) = 0;
};

struct ServiceOptions {
  // Per terrain package: decoded blocks, triangle errors and tiles cut on the fly.
  size_t cache_bytes = size_t(512) << 20;
  // The fontstack of the glyphs under /fonts (web/glyphs.hpp) the styles of
  // labelled packages write their names with; "" = none: no labels in the styles.
  std::string fontstack;
};

// Opens a package (or a .pmtiles file) as its service; `name` is its stem.
// Throws InputError naming the file if it cannot be read.
std::unique_ptr<PackageService> open_service(const std::string& path, const std::string& name,
                                             const ServiceOptions& options);

// A response with status, plain-text reason.
HttpResponse text_response(int status, const std::string& text);

}  // namespace globe::serve
