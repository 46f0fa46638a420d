// Opening a URL as the reader of its kind (see remote_open.hpp).
#include "data/remote_open.hpp"

#include "data/dem_open.hpp"
#include "data/pmtiles_fetcher.hpp"
#include "data/remote_image_reader.hpp"
#include "data/remote_reader.hpp"
#include "data/xyz_fetcher.hpp"
#include "net/url.hpp"
#include "runtime/errors.hpp"
#include "tileformat/json.hpp"

namespace globe::viewer {
namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  const std::string path = s.substr(0, s.find_first_of("?#"));
  return path.size() >= tail.size() &&
         path.compare(path.size() - tail.size(), tail.size(), tail) == 0;
}

// A raster fetcher as imagery, or as elevation when an encoding is named.
std::unique_ptr<tileformat::TileReader> raster_source(std::unique_ptr<RasterTileFetcher> fetcher,
                                                      const std::string& encoding) {
  if (!encoding.empty()) return open_raster_dem(std::move(fetcher), encoding);
  return std::make_unique<RemoteImageReader>(std::move(fetcher));
}

// A TileJSON without a "globe" member: its first raster template.
std::unique_ptr<tileformat::TileReader> foreign_tilejson(const std::string& url,
                                                         const tileformat::JsonValue& doc,
                                                         net::HttpClient& client,
                                                         const RemoteOptions& o) {
  const tileformat::JsonValue* tiles = doc.find("tiles");
  if (!tiles || !tiles->is_array() || tiles->array().empty() || !tiles->array()[0].is_string())
    throw InputError(url + ": a TileJSON without \"tiles\"");
  std::string tmpl = net::resolve_url(url, tiles->array()[0].string());
  const tileformat::JsonValue* scheme = doc.find("scheme");
  if (scheme && scheme->is_string() && scheme->string() == "tms") {
    const size_t at = tmpl.find("{y}");
    if (at != std::string::npos) tmpl.replace(at, 3, "{-y}");
  }
  const auto number = [&](const char* key, double fallback) {
    const tileformat::JsonValue* v = doc.find(key);
    return v && v->is_number() ? v->number() : fallback;
  };
  std::array<double, 4> bounds{-180, -85.0511287798, 180, 85.0511287798};
  if (const tileformat::JsonValue* b = doc.find("bounds");
      b && b->is_array() && b->array().size() == 4)
    for (size_t i = 0; i < 4; ++i)
      if (b->array()[i].is_number()) bounds[i] = b->array()[i].number();
  std::string encoding = o.dem_encoding;
  if (const tileformat::JsonValue* e = doc.find("encoding");
      encoding.empty() && e && e->is_string())
    encoding = e->string() == "mapbox" ? "terrain-rgb" : e->string();
  const std::string format =
      doc.find("format") && doc.find("format")->is_string() ? doc.find("format")->string() : "";
  if (format == "pbf" || format == "quantized-mesh-1.0")
    throw InputError(url + ": a TileJSON of " + format +
                     " tiles; globe-view reads globe-serve's TileJSON (with its \"globe\" member), "
                     "raster tiles, or quantized-mesh through layer.json");
  auto fetcher = std::make_unique<XyzFetcher>(tmpl, client, int(number("minzoom", 0)),
                                              int(number("maxzoom", 22)), bounds);
  return raster_source(std::move(fetcher), encoding);
}

}  // namespace

std::unique_ptr<tileformat::TileReader> open_remote(const std::string& url, net::HttpClient& client,
                                                    const RemoteOptions& o) {
  if (url.find("{z}") != std::string::npos) {
    const bool dem = !o.dem_encoding.empty();
    const auto [z0, z1] = o.source_zooms.value_or(std::pair{0, dem ? 15 : 19});
    return raster_source(std::make_unique<XyzFetcher>(url, client, z0, z1), o.dem_encoding);
  }
  if (ends_with(url, ".pmtiles"))
    return raster_source(std::make_unique<PmtilesFetcher>(url, client), o.dem_encoding);
  if (ends_with(url, "layer.json")) return open_quantized_mesh(url, client);
  net::Request req;
  req.url = url;
  req.accept_types = {"application/json", "text/plain"};
  const net::Response r = client.get_blocking(std::move(req));
  if (r.outcome != net::Outcome::kOk)
    throw InputError(url + ": cannot read it: " +
                     (r.error.empty() ? std::string(net::to_string(r.outcome)) : r.error));
  tileformat::JsonValue doc;
  try {
    doc = tileformat::JsonValue::parse(
        std::string_view(reinterpret_cast<const char*>(r.body.data()), r.body.size()));
  } catch (const std::exception& e) {
    throw InputError(url + ": not a TileJSON (" + e.what() +
                     "); globe-view reads TileJSON, XYZ templates ({z}/{x}/{y}), .pmtiles and "
                     "quantized-mesh layer.json URLs");
  }
  if (doc.find("globe")) return std::make_unique<RemoteReader>(url, doc, client);
  return foreign_tilejson(url, doc, client, o);
}

}  // namespace globe::viewer
