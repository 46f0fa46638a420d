// The services of the package kinds (see package_services.hpp).
#include "serve/package_services.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <mutex>
#include <set>
#include <span>
#include <thread>
#include <unordered_set>
#include <vector>

#include "runtime/area_package.hpp"
#include "runtime/errors.hpp"
#include "runtime/image_package.hpp"
#include "runtime/line_package.hpp"
#include "runtime/package_open.hpp"
#include "runtime/png_codec.hpp"
#include "runtime/point_package.hpp"
#include "runtime/terrain_package.hpp"
#include "serve/file_body.hpp"
#include "tileformat/feature_table.hpp"
#include "tileformat/image_tile.hpp"
#include "tileformat/json.hpp"
#include "web/area_mvt.hpp"
#include "web/line_mvt.hpp"
#include "web/lru_cache.hpp"
#include "web/mesh_tiles.hpp"
#include "web/mvt_encoder.hpp"
#include "web/mvt_labels.hpp"
#include "web/point_mvt.hpp"
#include "web/raster_dem.hpp"
#include "web/raster_dem_tile.hpp"
#include "web/terrain_sampler.hpp"
#include "web/vector_raster.hpp"

namespace globe::serve {
namespace {

using tileformat::TileId;

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

HttpResponse json_response(std::string body) {
  HttpResponse r;
  r.content_type = "application/json";
  r.body = std::move(body);
  r.compressible = true;
  return r;
}

HttpResponse bytes_response(std::vector<uint8_t> bytes, std::string type, bool compressible) {
  HttpResponse r;
  if (bytes.empty()) return text_response(204, "");
  r.content_type = std::move(type);
  r.body.assign(bytes.begin(), bytes.end());
  r.compressible = compressible;
  return r;
}

// The glyphs of a labelled package's style: /fonts on this server (`base`
// is http://host/NAME); none without labels or fonts.
web::StyleGlyphs style_glyphs(const web::MvtLabels& labels, const std::string& fontstack,
                              const std::string& base, const std::string& name) {
  if (labels.empty() || fontstack.empty()) return {};
  return {base.substr(0, base.size() - name.size() - 1) + "/fonts/{fontstack}/{range}.pbf",
          fontstack};
}

// TileJSON 3.0.0 of a tile set under `base`.
std::string tilejson_text(const TileSetExtent& s, const std::string& name,
                          const std::string& tiles_url, const std::string& extra,
                          bool tms = false) {
  return "{\"tilejson\":\"3.0.0\",\"name\":\"" + tileformat::json_escape(name) +
         "\",\"tiles\":[\"" + tileformat::json_escape(tiles_url) + "\"],\"scheme\":\"" +
         (tms ? "tms" : "xyz") + "\",\"minzoom\":" + std::to_string(s.min_zoom) +
         ",\"maxzoom\":" + std::to_string(s.max_zoom) + ",\"bounds\":[" + number(s.west) + "," +
         number(s.south) + "," + number(s.east) + "," + number(s.north) + "]" +
         (extra.empty() ? "" : "," + extra) + "}";
}

class TerrainService : public PackageService {
 public:
  // The memory budget: most for triangle errors (264 KB a tile of 257²
  // samples, needed by its eight neighbours too), a quarter for decoded
  // blocks, an eighth for cut tiles.
  TerrainService(const std::string& path, const std::string& name, size_t cache_bytes)
      : pkg_(open_terrain_package(path)),
        name_(name),
        blocks_(pkg_, cache_bytes / 4),
        own_errors_(cache_bytes * 5 / 8),
        tiles_(cache_bytes / 8) {
    const tileformat::Bounds& b = pkg_.meta.common.lonlat;
    west = b.min_x, south = b.min_y, east = b.max_x, north = b.max_y;
    min_zoom = 0, max_zoom = pkg_.max_zoom;
    if (pkg_.tiling.scheme == tileformat::Scheme::kLocal) return;
    plan_ = web::mesh_tile_plan(pkg_);
    for (const auto& level : plan_)
      for (const TileId& id : level)
        planned_.insert(web::tile_key(id));
    layer_json_ =
        web::layer_json(pkg_, plan_, name, "Heights of " + name + " served by globe-serve", true);
    const double finer = std::log2(2.0 * (pkg_.block_size - 1) / 256);
    dem_max_zoom_ = pkg_.tiling.scheme == tileformat::Scheme::kWebMercator
                        ? pkg_.max_zoom
                        : std::clamp(int(std::floor(pkg_.max_zoom + finer + 1e-9)), 0, 24);
  }
  std::string kind() const override { return "terrain"; }
  std::string tiling() const override { return tileformat::scheme_name(pkg_.tiling.scheme); }

  // The quantized-mesh tiles (TMS rows), or with ?encoding=terrarium|terrain-rgb
  // the raster-DEM PNGs (XYZ rows, web mercator zooms), as MapLibre's
  // raster-dem source reads them.
  HttpResponse tilejson(const std::string& base, const HttpRequest& req) override {
    const auto enc = req.query.find("encoding");
    if (enc == req.query.end())
      return json_response(tilejson_text(*this, name_, base + "/{z}/{x}/{y}.terrain",
                                         "\"format\":\"quantized-mesh-1.0\",\"raster_dem\":\"" +
                                             base + "/{z}/{x}/{y}.png?encoding=terrarium\"",
                                         true));
    const std::string encoding = enc->second == "mapbox" ? "terrain-rgb" : enc->second;
    if (encoding != "terrarium" && encoding != "terrain-rgb")
      return text_response(400, "encoding: terrarium or terrain-rgb");
    TileSetExtent dem = *this;
    dem.min_zoom = 0, dem.max_zoom = dem_max_zoom_;
    dem.south = std::max(south, -85.0511287798), dem.north = std::min(north, 85.0511287798);
    return json_response(tilejson_text(
        dem, name_, base + "/{z}/{x}/{y}.png?encoding=" + encoding,
        "\"format\":\"png\",\"encoding\":\"" +
            std::string(encoding == "terrarium" ? "terrarium" : "mapbox") + "\",\"tileSize\":256"));
  }

  HttpResponse answer(const Route& r, const HttpRequest& req, const std::string&) override {
    if (pkg_.tiling.scheme == tileformat::Scheme::kLocal)
      return text_response(404, name_ + " is in a local tiling, which web clients cannot place");
    if (r.kind == Route::Kind::kLayerJson) return json_response(layer_json_);
    if (r.kind != Route::Kind::kTile)
      return text_response(404, "a terrain package has no " + std::string("style.json"));
    if (r.extension == "terrain") return mesh_tile(r, req);
    if (r.extension == "png") return dem_tile(r, req);
    return text_response(404, "terrain tiles are .terrain (quantized-mesh) and .png (raster-DEM)");
  }

 private:
  HttpResponse mesh_tile(const Route& r, const HttpRequest& req) {
    const tileformat::Tiling& t = pkg_.tiling;
    if (r.z > pkg_.max_zoom)
      return text_response(404, "zoom " + std::to_string(r.z) + " is beyond the package's " +
                                    std::to_string(pkg_.max_zoom));
    if (r.x >= t.tiles_x(r.z) || r.y >= t.tiles_y(r.z))
      return text_response(404, "tile " + std::to_string(r.x) + "/" + std::to_string(r.y) +
                                    " is outside zoom " + std::to_string(r.z));
    const TileId id{r.z, r.x, uint32_t(t.tiles_y(r.z) - 1 - r.y)};  // TMS row to ours
    if (!planned_.count(web::tile_key(id))) return text_response(204, "");
    const auto ext = req.query.find("extensions");
    web::MeshTileOptions options;
    options.finest_zoom = pkg_.max_zoom;
    options.normals =
        req.header("accept").find("octvertexnormals") != std::string::npos ||
        (ext != req.query.end() && ext->second.find("octvertexnormals") != std::string::npos);
    const std::string cache_key = "q" + std::to_string(r.z) + "/" + std::to_string(r.x) + "/" +
                                  std::to_string(r.y) + (options.normals ? "n" : "");
    if (auto hit = tiles_.get(cache_key))
      return bytes_response({hit->begin(), hit->end()}, "application/vnd.quantized-mesh", true);
    const CutSlot slot(cutting_);
    web::MeshTileSource source(blocks_, own_errors_);
    const web::TileGrid grid = source.grid(id);
    const web::MeshErrors errors = source.errors(id, options.threshold(id.z, t.roots_x));
    std::vector<uint8_t> bytes = web::encode_mesh_tile(t, id, grid, errors, options);
    tiles_.put(cache_key, std::make_shared<const std::string>(bytes.begin(), bytes.end()),
               cache_key.size() + bytes.size());
    return bytes_response(std::move(bytes), "application/vnd.quantized-mesh", true);
  }

  HttpResponse dem_tile(const Route& r, const HttpRequest& req) {
    const auto enc = req.query.find("encoding");
    web::DemEncoding encoding = web::DemEncoding::kTerrarium;
    if (enc != req.query.end()) {
      if (enc->second == "terrain-rgb" || enc->second == "mapbox")
        encoding = web::DemEncoding::kTerrainRgb;
      else if (enc->second != "terrarium")
        return text_response(400, "encoding: terrarium or terrain-rgb");
    }
    if (r.z > dem_max_zoom_)
      return text_response(404, "raster-DEM zoom " + std::to_string(r.z) + " is beyond " +
                                    std::to_string(dem_max_zoom_));
    if (r.x >= (uint64_t{1} << r.z) || r.y >= (uint64_t{1} << r.z))
      return text_response(404, "tile outside zoom " + std::to_string(r.z));
    const std::string cache_key = "d" + std::to_string(int(encoding)) + "/" + std::to_string(r.z) +
                                  "/" + std::to_string(r.x) + "/" + std::to_string(r.y);
    if (auto hit = tiles_.get(cache_key))
      return bytes_response({hit->begin(), hit->end()}, "image/png", false);
    const CutSlot slot(cutting_);
    web::TerrainSampler sampler(blocks_);
    std::vector<uint8_t> png = web::raster_dem_tile(sampler, pkg_.tiling, r.z, r.x, r.y, 256,
                                                    web::raster_dem_source_zoom(pkg_, r.z, 256),
                                                    encoding, nullptr, web::kPngFast);
    tiles_.put(cache_key, std::make_shared<const std::string>(png.begin(), png.end()),
               cache_key.size() + png.size());
    return bytes_response(std::move(png), "image/png", false);
  }

  TerrainPackage pkg_;
  std::string name_, layer_json_;
  std::vector<std::vector<TileId>> plan_;
  std::unordered_set<uint64_t> planned_;
  int dem_max_zoom_ = 0;
  web::TerrainBlocks blocks_;
  web::OwnErrorCache own_errors_;
  web::LruCache<std::string, std::string> tiles_;  // tiles cut on the fly
  // Tiles cut at once: at most one per core, however many requests the HTTP
  // threads are working on. Cutting is CPU work, so more at once is not
  // faster, and each holds its blocks' grids and errors (about 2.5 MB at
  // 257² samples): 100 clients asking new tiles of a package at once took
  // 64 such working sets with the old thread-per-connection server (issue
  // 55: peak RSS 607-648 MB with --cache-mb 256). Cache hits never wait.
  // (A mutex and a condition variable: libstdc++'s counting_semaphore spins
  // before it sleeps, which a thread waiting for a busy core should not.)
  struct CutSlots {
    std::mutex mutex;
    std::condition_variable freed;
    int free = int(std::max(1u, std::thread::hardware_concurrency()));
  } cutting_;
  struct CutSlot {
    explicit CutSlot(CutSlots& s) : s_(s) {
      std::unique_lock lock(s_.mutex);
      s_.freed.wait(lock, [&] { return s_.free > 0; });
      --s_.free;
    }
    ~CutSlot() {
      {
        std::lock_guard lock(s_.mutex);
        ++s_.free;
      }
      s_.freed.notify_one();
    }
    CutSlots& s_;
  };
};

// A tile of a global tiling (web mercator or geodetic: CesiumJS drapes
// images in both) inside the package's zooms, or the refusal.
HttpResponse check_tile(const tileformat::Tiling& t, const std::string& name, const Route& r,
                        int min_zoom, int max_zoom) {
  if (t.scheme == tileformat::Scheme::kLocal)
    return text_response(404, name + " is in a local tiling, which web clients cannot place");
  if (r.z < min_zoom || r.z > max_zoom)
    return text_response(404, "zoom " + std::to_string(r.z) + " is outside the package's " +
                                  std::to_string(min_zoom) + ".." + std::to_string(max_zoom));
  if (r.x >= t.tiles_x(r.z) || r.y >= t.tiles_y(r.z))
    return text_response(404, "tile outside zoom " + std::to_string(r.z));
  return HttpResponse{};
}

// A tile with nothing drawn: fully transparent, so that an image client
// draws what lies under it (a 204 is an error to CesiumJS's imagery).
HttpResponse transparent_png() {
  static const std::vector<uint8_t> png = [] {
    const std::vector<uint8_t> clear(size_t(256) * 256 * 4, 0);
    return encode_png(clear.data(), 256, 256, 4, 9);
  }();
  return bytes_response(png, "image/png", false);
}

// Web mercator packages only (vector tiles for web maps): their rows are
// XYZ rows.
HttpResponse check_xyz(const tileformat::Tiling& t, const std::string& name, const Route& r,
                       int min_zoom, int max_zoom) {
  if (t.scheme != tileformat::Scheme::kWebMercator)
    return text_response(404, name + " is not in the webmercator tiling; web maps read only that");
  return check_tile(t, name, r, min_zoom, max_zoom);
}

class ImageService : public PackageService {
 public:
  ImageService(const std::string& path, const std::string& name)
      : pkg_(open_image_package(path)), name_(name) {
    const tileformat::Bounds& b = pkg_.meta.common.lonlat;
    west = b.min_x, south = b.min_y, east = b.max_x, north = b.max_y;
    min_zoom = pkg_.min_zoom, max_zoom = pkg_.max_zoom;
    ext_ = tileformat::image_format_name(pkg_.format);
  }
  std::string kind() const override { return "images"; }
  std::string tiling() const override { return tileformat::scheme_name(pkg_.tiling.scheme); }
  HttpResponse tilejson(const std::string& base, const HttpRequest&) override {
    return json_response(tilejson_text(
        *this, name_, base + "/{z}/{x}/{y}." + ext_,
        "\"format\":\"" + ext_ + "\",\"tileSize\":" + std::to_string(pkg_.tile_size)));
  }
  HttpResponse answer(const Route& r, const HttpRequest&, const std::string&) override {
    if (r.kind != Route::Kind::kTile) return text_response(404, "an image package has tiles only");
    if (r.extension != ext_)
      return text_response(404, name_ + " holds ." + ext_ + " tiles, not ." + r.extension);
    // Web mercator for every client, geodetic for CesiumJS (its geographic
    // tiling scheme): rows from the north in both.
    HttpResponse bad = check_tile(pkg_.tiling, name_, r, min_zoom, max_zoom);
    if (bad.status != 200) return bad;
    std::optional<std::vector<uint8_t>> tile;
    {
      std::lock_guard lock(mutex_);
      tile = pkg_.reader->tile({r.z, r.x, r.y});
    }
    if (!tile) return text_response(204, "");
    return bytes_response(std::move(*tile), ext_ == "jpg" ? "image/jpeg" : "image/" + ext_, false);
  }

 private:
  ImagePackage pkg_;
  std::string name_, ext_;
  std::mutex mutex_;
};

// Vector tiles: gzip where the client accepts it (the HTTP layer).
// The routes every vector package answers (lines, areas): its MapLibre style,
// its tiles drawn as PNG for image clients (any tiling) and as MVT (web
// mercator: check_xyz). `what` names the package in the 404 ("a line
// package"); the reader and the encoders are used under `mutex` (one SQLite
// connection, one features cache).
HttpResponse answer_vector_route(
    const Route& r, const std::string& name, const tileformat::Tiling& tiling, int min_zoom,
    int max_zoom, std::mutex& mutex, tileformat::PackageReader& reader, const std::string& what,
    const std::function<std::string()>& style,
    const std::function<std::vector<uint8_t>(tileformat::TileId, std::span<const uint8_t>)>& png,
    const std::function<std::vector<uint8_t>(tileformat::TileId, std::span<const uint8_t>)>& mvt) {
  if (r.kind == Route::Kind::kStyleJson) return json_response(style());
  const tileformat::TileId id{r.z, r.x, r.y};
  if (r.kind == Route::Kind::kTile && r.extension == "png") {
    HttpResponse bad = check_tile(tiling, name, r, min_zoom, max_zoom);
    if (bad.status != 200) return bad;
    std::optional<std::vector<uint8_t>> blob;
    {
      std::lock_guard lock(mutex);
      blob = reader.tile(id);
    }
    std::vector<uint8_t> drawn;
    if (blob) drawn = png(id, *blob);
    return drawn.empty() ? transparent_png() : bytes_response(std::move(drawn), "image/png", false);
  }
  if (r.kind != Route::Kind::kTile || (r.extension != "pbf" && r.extension != "mvt"))
    return text_response(404, what + " has style.json, .pbf and .png tiles");
  HttpResponse bad = check_xyz(tiling, name, r, min_zoom, max_zoom);
  if (bad.status != 200) return bad;
  std::lock_guard lock(mutex);
  const auto blob = reader.tile(id);
  if (!blob) return text_response(204, "");
  return bytes_response(mvt(id, *blob), "application/vnd.mapbox-vector-tile", true);
}

class LineService : public PackageService {
 public:
  LineService(const std::string& path, const std::string& name, const std::string& fontstack)
      : pkg_(open_line_package(path)), name_(name), fontstack_(fontstack), encoder_(pkg_) {
    const tileformat::Bounds& b = pkg_.meta.common.lonlat;
    west = b.min_x, south = b.min_y, east = b.max_x, north = b.max_y;
    min_zoom = pkg_.min_zoom, max_zoom = pkg_.max_zoom;
    // Every class in every layer of the features table.
    std::set<uint32_t> all;
    for (uint32_t c = 0; c < pkg_.classes.size(); ++c)
      all.insert(c);
    for (const tileformat::LineLayerInfo& l : pkg_.meta.layers)
      classes_in_[l.name.empty() ? "lines" : l.name] = all;
    if (classes_in_.empty()) classes_in_["lines"] = all;
  }
  std::string kind() const override { return "lines"; }
  std::string tiling() const override { return tileformat::scheme_name(pkg_.tiling.scheme); }
  HttpResponse tilejson(const std::string& base, const HttpRequest&) override {
    std::map<std::string, std::map<std::string, std::string>> layers;
    for (const auto& [layer, _] : classes_in_) {
      layers[layer]["class"] = "String";
      if (!encoder_.labels().empty()) layers[layer]["name"] = "String";
    }
    return json_response(
        tilejson_text(*this, name_, base + "/{z}/{x}/{y}.pbf",
                      "\"format\":\"pbf\",\"vector_layers\":" + web::vector_layers_json(layers)));
  }
  HttpResponse answer(const Route& r, const HttpRequest&, const std::string& base) override {
    return answer_vector_route(
        r, name_, pkg_.tiling, min_zoom, max_zoom, mutex_, pkg_.file(), "a line package",
        [&] {
          return web::line_style_json(pkg_, classes_in_, base + ".json",
                                      style_glyphs(encoder_.labels(), fontstack_, base, name_));
        },
        [&](tileformat::TileId id, std::span<const uint8_t> blob) {
          return web::line_tile_png(pkg_, id, blob);
        },
        [&](tileformat::TileId id, std::span<const uint8_t> blob) {
          return encoder_.encode(id, blob);
        });
  }

 private:
  LinePackage pkg_;
  std::string name_, fontstack_;
  web::LineMvtEncoder encoder_;
  std::map<std::string, std::set<uint32_t>> classes_in_;
  std::mutex mutex_;
};

class PointService : public PackageService {
 public:
  PointService(const std::string& path, const std::string& name, const std::string& fontstack)
      : pkg_(open_point_package(path)), name_(name), fontstack_(fontstack), labels_(pkg_.file()) {
    const tileformat::Bounds& b = pkg_.meta.common.lonlat;
    west = b.min_x, south = b.min_y, east = b.max_x, north = b.max_y;
    min_zoom = pkg_.meta.common.min_zoom, max_zoom = pkg_.meta.common.max_zoom;
  }
  std::string kind() const override { return "points"; }
  std::string tiling() const override {
    return tileformat::scheme_name(pkg_.meta.common.tiling.scheme);
  }
  HttpResponse tilejson(const std::string& base, const HttpRequest&) override {
    return json_response(
        tilejson_text(*this, name_, base + "/{z}/{x}/{y}.pbf",
                      "\"format\":\"pbf\",\"vector_layers\":" +
                          web::vector_layers_json(web::point_mvt_fields(pkg_, &labels_))));
  }
  HttpResponse answer(const Route& r, const HttpRequest&, const std::string& base) override {
    if (r.kind == Route::Kind::kStyleJson)
      return json_response(web::point_style_json(pkg_, base + ".json",
                                                 style_glyphs(labels_, fontstack_, base, name_)));
    if (r.kind == Route::Kind::kTile && r.extension == "png") {  // drawn, for image clients
      HttpResponse bad = check_tile(pkg_.meta.common.tiling, name_, r, min_zoom, max_zoom);
      if (bad.status != 200) return bad;
      const std::vector<uint8_t> png = web::point_tile_png(pkg_, {r.z, r.x, r.y}, [&](TileId t) {
        std::lock_guard lock(mutex_);
        return pkg_.reader->tile(t);
      });
      return png.empty() ? transparent_png() : bytes_response(std::move(png), "image/png", false);
    }
    if (r.kind != Route::Kind::kTile || (r.extension != "pbf" && r.extension != "mvt"))
      return text_response(404, "a point package has style.json, .pbf and .png tiles");
    HttpResponse bad = check_xyz(pkg_.meta.common.tiling, name_, r, min_zoom, max_zoom);
    if (bad.status != 200) return bad;
    std::optional<std::vector<uint8_t>> blob;
    {
      std::lock_guard lock(mutex_);
      blob = pkg_.reader->tile({r.z, r.x, r.y});
    }
    if (!blob) return text_response(204, "");
    return bytes_response(web::point_tile_mvt(pkg_, {r.z, r.x, r.y}, *blob, nullptr, &labels_),
                          "application/vnd.mapbox-vector-tile", true);
  }

 private:
  PointPackage pkg_;
  std::string name_, fontstack_;
  const web::MvtLabels labels_;
  std::mutex mutex_;
};

// Areas as lines are served: MVT (web mercator), the style, drawn PNGs (web
// mercator and geodetic).
class AreaService : public PackageService {
 public:
  AreaService(const std::string& path, const std::string& name, const std::string& fontstack)
      : pkg_(open_area_package(path)), name_(name), fontstack_(fontstack), encoder_(pkg_) {
    const tileformat::CommonMetadata& c = pkg_.meta.common;
    west = c.lonlat.min_x, south = c.lonlat.min_y, east = c.lonlat.max_x, north = c.lonlat.max_y;
    min_zoom = c.min_zoom, max_zoom = c.max_zoom;
    // The layers (as the encoder names them) with every class, and their
    // fields: the class (a number in a choropleth, the class name
    // otherwise), the choropleth's value, and the attributes of the first
    // 10,000 features (a package's features share their source's fields).
    std::set<uint32_t> all;
    if (const auto& ch = pkg_.meta.choropleth) {
      for (uint32_t k = 0; k <= ch->classes.size(); ++k)
        all.insert(k);
    } else {
      for (uint32_t k = 0; k < pkg_.classes.size(); ++k)
        all.insert(k);
    }
    for (const tileformat::LineLayerInfo& l : pkg_.meta.layers)
      fields_[l.name.empty() ? "areas" : l.name];
    struct Enough {};
    int64_t read = 0;
    try {
      tileformat::FeatureTableReader(pkg_.file())
          .for_each([&](int64_t, const tileformat::FeatureRecord& f) {
            if (++read > 10000) throw Enough{};
            std::map<std::string, std::string>& known =
                fields_[f.layer.empty() ? "areas" : f.layer];
            try {
              const tileformat::JsonValue props = tileformat::JsonValue::parse(f.properties);
              if (props.is_object())
                for (const auto& [k, v] : props.members())
                  if (k != "class" && k != "value")  // as the encoder: these are its own
                    known.try_emplace(k, v.is_number() ? "Number"
                                         : v.is_bool() ? "Boolean"
                                                       : "String");
            } catch (const tileformat::JsonError&) {
              // attributes that are not JSON: the encoder leaves them out too
            }
          });
    } catch (const Enough&) {
    }
    if (fields_.empty()) fields_["areas"];
    for (auto& [layer, fields] : fields_) {
      classes_in_[layer] = all;
      fields["class"] = pkg_.meta.choropleth ? "Number" : "String";
      if (pkg_.meta.choropleth) fields["value"] = "Number";
      if (!encoder_.labels().empty()) fields["name"] = "String";
    }
    // The label points (one per labelled area, web/area_mvt.hpp).
    if (!encoder_.labels().empty())
      fields_[web::area_label_layer(pkg_)] = {{"name", "String"}, {"rank", "Number"}};
  }
  std::string kind() const override { return "areas"; }
  std::string tiling() const override {
    return tileformat::scheme_name(pkg_.meta.common.tiling.scheme);
  }
  HttpResponse tilejson(const std::string& base, const HttpRequest&) override {
    return json_response(
        tilejson_text(*this, name_, base + "/{z}/{x}/{y}.pbf",
                      "\"format\":\"pbf\",\"vector_layers\":" + web::vector_layers_json(fields_)));
  }
  HttpResponse answer(const Route& r, const HttpRequest&, const std::string& base) override {
    return answer_vector_route(
        r, name_, pkg_.meta.common.tiling, min_zoom, max_zoom, mutex_, pkg_.file(),
        "an area package",
        [&] {
          return web::area_style_json(pkg_, classes_in_, base + ".json",
                                      style_glyphs(encoder_.labels(), fontstack_, base, name_));
        },
        [&](tileformat::TileId id, std::span<const uint8_t> blob) {
          return web::area_tile_png(pkg_, id, blob);
        },
        [&](tileformat::TileId id, std::span<const uint8_t> blob) {
          return encoder_.encode(id, blob);
        });
  }

 private:
  AreaPackage pkg_;
  std::string name_, fontstack_;
  web::AreaMvtEncoder encoder_;
  std::map<std::string, std::set<uint32_t>> classes_in_;
  std::map<std::string, std::map<std::string, std::string>> fields_;
  std::mutex mutex_;
};

// A PMTiles v3 archive: its bytes, read on demand (ranges, validators:
// file_body.hpp and the request handler).
class PmtilesService : public PackageService {
 public:
  PmtilesService(const std::string& path, const std::string& name)
      : file_(OpenFile::open(path)), name_(name) {
    if (!file_) throw InputError(path + ": cannot open (" + std::strerror(errno) + ")");
    unsigned char h[127];
    if (::pread(file_->fd(), h, sizeof h, 0) != ssize_t(sizeof h) ||
        std::memcmp(h, "PMTiles", 7) != 0 || h[7] != 3)
      throw InputError(path + ": not a PMTiles v3 archive (the header's magic or version)");
    auto i32 = [&](int at) {
      return int32_t(uint32_t(h[at]) | uint32_t(h[at + 1]) << 8 | uint32_t(h[at + 2]) << 16 |
                     uint32_t(h[at + 3]) << 24);
    };
    min_zoom = h[100], max_zoom = h[101];
    west = i32(102) / 1e7, south = i32(106) / 1e7, east = i32(110) / 1e7, north = i32(114) / 1e7;
  }
  std::string kind() const override { return "pmtiles"; }
  std::string tiling() const override { return ""; }
  HttpResponse tilejson(const std::string&, const HttpRequest&) override {
    return text_response(404, name_ +
                                  ".pmtiles holds its own metadata; read it with a PMTiles "
                                  "client from /" +
                                  name_ + ".pmtiles");
  }
  HttpResponse answer(const Route& r, const HttpRequest&, const std::string&) override {
    if (r.kind != Route::Kind::kPmtiles)
      return text_response(404, name_ + " is a PMTiles archive: /" + name_ + ".pmtiles");
    return file_response(file_, "application/vnd.pmtiles");
  }

 private:
  std::shared_ptr<const OpenFile> file_;
  std::string name_;
};

}  // namespace

HttpResponse text_response(int status, const std::string& text) {
  HttpResponse r;
  r.status = status;
  r.body = text.empty() ? text : text + "\n";
  return r;
}

static std::unique_ptr<PackageService> open_kind_service(const std::string& path,
                                                         const std::string& name,
                                                         const ServiceOptions& options);

std::unique_ptr<PackageService> open_service(const std::string& path, const std::string& name,
                                             const ServiceOptions& options) {
  if (path.size() > 8 && path.compare(path.size() - 8, 8, ".pmtiles") == 0)
    return std::make_unique<PmtilesService>(path, name);
  std::unique_ptr<PackageService> service = open_kind_service(path, name, options);
  try {
    service->native = std::make_unique<NativeTiles>(path);
  } catch (const tileformat::PackageError& e) {
    throw InputError(e.what());
  }
  return service;
}

std::unique_ptr<PackageService> open_kind_service(const std::string& path, const std::string& name,
                                                  const ServiceOptions& options) {
  const std::optional<tileformat::PackageKind> kind = package_kind(path);
  if (!kind) throw InputError(path + ": not a package of this project nor a .pmtiles file");
  switch (*kind) {
    case tileformat::PackageKind::kTerrain:
      return std::make_unique<TerrainService>(path, name, options.cache_bytes);
    case tileformat::PackageKind::kImage:
      return std::make_unique<ImageService>(path, name);
    case tileformat::PackageKind::kLines:
      return std::make_unique<LineService>(path, name, options.fontstack);
    case tileformat::PackageKind::kPoints:
      return std::make_unique<PointService>(path, name, options.fontstack);
    case tileformat::PackageKind::kAreas:
      return std::make_unique<AreaService>(path, name, options.fontstack);
    case tileformat::PackageKind::kAnalysis:
      throw InputError(path +
                       ": analysis packages have no web format yet; serve the terrain package");
    default:  // a kind without a service
      throw InputError(path + ": " + tileformat::package_kind_name(*kind) +
                       " packages have no web format yet");
  }
}

}  // namespace globe::serve
