// globe-serve (docs/serve.md) as users run it, over a raw HTTP client
// written in the test (serve_fixtures.hpp): the tiles it cuts on the fly are
// the exports' bytes (themselves checked against the spec readers and
// analytic surfaces in web_quantized_mesh_test.cpp and web_export_test.cpp),
// the HTTP contract (status codes, ETag, CORS, gzip, ranges), a hostile
// request corpus after which it still serves, and packages replaced on disk.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <random>
#include <set>
#include <string_view>
#include <thread>

#include <ogr_api.h>
#include <ogr_srs_api.h>

#include "area_fixtures.hpp"
#include "serve_fixtures.hpp"
#include "spec_readers/gunzip.hpp"
#include "spec_readers/pmtiles_reader.hpp"
#include "spec_readers/quantized_mesh_reader.hpp"
#include "test_paths.hpp"
#include "test_support.hpp"
#include "tileformat/json.hpp"
#include "web_fixtures.hpp"
#include "web_surfaces.hpp"

namespace {

using namespace globe_test;
namespace pmr = spec_readers::pmtiles;

// A line package and a point package of a few European features, built once.
const fs::path& vector_packages() {
  static const fs::path dir = shared_folder("serve-vectors", [](const fs::path& d) {
    std::ofstream(d / "roads.geojson")
        << R"({"type":"FeatureCollection","features":[)"
        << R"({"type":"Feature","properties":{"kind":"road","name":"A1"},"geometry":{"type":"LineString","coordinates":[[6.1,46.2],[6.6,46.5],[7.4,46.9],[8.5,47.4],[9.4,47.4]]}},)"
        << R"({"type":"Feature","properties":{"kind":"river","name":"Aare"},"geometry":{"type":"LineString","coordinates":[[7.0,46.9],[7.4,46.95],[7.9,47.3],[8.2,47.6]]}}]})";
    std::ofstream(d / "towns.csv") << "lon,lat,people\n7.45,46.95,134000\n8.54,47.37,421000\n"
                                      "6.14,46.2,203000\n7.59,47.56,173000\n";
    return run_all(
        {vectorize() + " lines -q " + (d / "roads.geojson").string() +
             " --class-field kind --max-zoom 8 -o " + (d / "roads.mbtiles").string(),
         vectorize() + " points -q " + (d / "towns.csv").string() +
             " --xy lon,lat --fields people --max-zoom 8 -o " + (d / "towns.mbtiles").string()},
        d);
  });
  return dir;
}

std::string gunzip(const std::string& bytes) {
  return spec_readers::gunzip(bytes, "test: ", size_t(1) << 30);
}

// The choropleth classes `globe-vectorize info --json` lists: [min, max) each,
// the last [min, max].
struct ChoroplethClass {
  double min = 0, max = 0;
  std::string color;
};

std::vector<ChoroplethClass> choropleth_classes(const std::string& package, const fs::path& dir) {
  std::vector<ChoroplethClass> out;
  const RunResult info = run(vectorize() + " info --json " + package, dir);
  EXPECT_EQ(info.exit_code, 0) << info.err;
  if (info.exit_code != 0) return out;
  const tileformat::JsonValue json = tileformat::JsonValue::parse(info.out);
  for (const auto& c : json.find("areas")->find("classes")->array())
    out.push_back({c.find("min")->number(), c.find("max")->number(), c.find("color")->string()});
  return out;
}

// The class (1..k) of a value, as the package's classes say: the last whose
// minimum it reaches; 0 outside them all.
int class_of(const std::vector<ChoroplethClass>& classes, double v) {
  int k = 0;
  for (size_t i = 0; i < classes.size(); ++i)
    if (v >= classes[i].min) k = int(i) + 1;
  return k > 0 && v <= classes.back().max ? k : 0;
}

// "#rrggbb" as three bytes.
std::vector<int> rgb_of(const std::string& hex) {
  unsigned r = 0, g = 0, b = 0;
  std::sscanf(hex.c_str(), "#%2x%2x%2x", &r, &g, &b);
  return {int(r), int(g), int(b)};
}

}  // namespace

// Quantized-mesh and raster-DEM tiles cut on the fly equal the exports';
// layer.json lists the same tiles; 204 inside the pyramid, 404 past it, 400
// for malformed paths.
TEST(Serve, TerrainTilesAreTheExportsBytes) {
  TempDir dir("serve-terrain");
  const fs::path pkg = dir / "surf.mbtiles";
  fs::copy_file(surface_dem() / "geodetic.mbtiles", pkg);
  ASSERT_TRUE(run_all({tiler() + " export -q " + pkg.string() + " --format quantized-mesh -o " +
                           (dir / "qm").string(),
                       tiler() + " export -q " + pkg.string() + " --format terrarium -o " +
                           (dir / "t.pmtiles").string()},
                      dir.path()));
  ServeProcess server({pkg.string()}, dir.path());
  ASSERT_GT(server.port(), 0) << server.log();
  const int port = server.port();

  const HttpReply layer = http_get(port, "/surf/layer.json");
  ASSERT_EQ(layer.status, 200);
  const auto served = tileformat::JsonValue::parse(layer.body);
  const auto exported = tileformat::JsonValue::parse(read_file(dir / "qm" / "layer.json"));
  EXPECT_EQ(served.find("available")->text(), exported.find("available")->text());
  EXPECT_EQ(served.find("tiles")->text(), exported.find("tiles")->text());

  size_t tiles = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir / "qm")) {
    if (e.path().extension() != ".terrain") continue;
    const std::string rel = fs::relative(e.path(), dir / "qm").string();
    const HttpReply r = http_get(port, "/surf/" + rel + "?v=1.0.0&extensions=octvertexnormals");
    ASSERT_EQ(r.status, 200) << rel << ": " << r.body;
    EXPECT_EQ(r.header("content-type"), "application/vnd.quantized-mesh");
    EXPECT_TRUE(r.body == read_file(e.path())) << rel << " differs from the export";
    ++tiles;
  }
  EXPECT_GT(tiles, 10u);
  // Negotiated extensions: without them no normals; gzip when accepted.
  const HttpReply plain = http_get(port, "/surf/0/1/0.terrain");
  ASSERT_EQ(plain.status, 200);
  EXPECT_FALSE(spec_readers::quantized_mesh::decode(plain.body).has_normals());
  const HttpReply zipped =
      http_get(port, "/surf/0/1/0.terrain",
               "Accept: application/vnd.quantized-mesh;extensions=octvertexnormals\r\n"
               "Accept-Encoding: gzip, deflate\r\n");
  ASSERT_EQ(zipped.status, 200);
  EXPECT_EQ(zipped.header("content-encoding"), "gzip");
  EXPECT_TRUE(spec_readers::quantized_mesh::decode(gunzip(zipped.body)).has_normals());

  // Raster-DEM PNG: the Terrarium PMTiles export's pixels (the server codes
  // its PNGs for speed, the export for size).
  const std::string archive = read_file(dir / "t.pmtiles");
  const pmr::Header h = pmr::read_header(archive);
  size_t pngs = 0;
  for (const pmr::Entry& entry : pmr::validate_archive(archive)) {
    const pmr::TileCoord t = pmr::tile_id_to_zxy(entry.tile_id);
    if (pngs >= 12) break;
    const HttpReply r = http_get(port, "/surf/" + std::to_string(t.z) + "/" + std::to_string(t.x) +
                                           "/" + std::to_string(t.y) + ".png?encoding=terrarium");
    ASSERT_EQ(r.status, 200) << int(t.z) << "/" << t.x << "/" << t.y;
    EXPECT_EQ(r.header("content-type"), "image/png");
    int w = 0, hgt = 0, ew = 0, eh = 0;
    const std::vector<uint8_t> served = png_rgb(r.body, w, hgt);
    const std::vector<uint8_t> exported =
        png_rgb(archive.substr(h.tile_data_offset + entry.offset, entry.length), ew, eh);
    EXPECT_EQ(w, 256);
    EXPECT_EQ(hgt, 256);
    EXPECT_TRUE(served == exported) << int(t.z) << "/" << t.x << "/" << t.y;
    ++pngs;
  }
  EXPECT_GT(pngs, 5u);
  // Their TileJSON for MapLibre's raster-dem source: the export's zooms.
  const HttpReply dem = http_get(port, "/surf.json?encoding=terrarium");
  ASSERT_EQ(dem.status, 200) << dem.body;
  const auto dj = tileformat::JsonValue::parse(dem.body);
  EXPECT_EQ(
      dj.find("tiles")->array().at(0).string(),
      "http://127.0.0.1:" + std::to_string(port) + "/surf/{z}/{x}/{y}.png?encoding=terrarium");
  EXPECT_EQ(dj.find("encoding")->string(), "terrarium");
  EXPECT_EQ(int(dj.find("minzoom")->number()), int(h.min_zoom));
  EXPECT_EQ(int(dj.find("maxzoom")->number()), int(h.max_zoom));
  EXPECT_EQ(http_get(port, "/surf.json?encoding=lerc").status, 400);

  // The pyramid's edges.
  EXPECT_EQ(http_get(port, "/surf/7/0/0.terrain").status, 204);  // zoom 7, no data there
  EXPECT_EQ(http_get(port, "/surf/8/0/0.terrain").status, 404);  // past the finest zoom
  EXPECT_EQ(http_get(port, "/surf/99/0/0.terrain").status, 404);
  EXPECT_EQ(http_get(port, "/surf/2/99/0.terrain").status, 404);  // outside zoom 2
  EXPECT_EQ(http_get(port, "/surf/2/a/0.terrain").status, 400);
  EXPECT_EQ(http_get(port, "/surf/02/0/0.terrain").status, 400);
  EXPECT_EQ(http_get(port, "/surf/2/0/0.gif").status, 400);
  EXPECT_EQ(http_get(port, "/nope/2/0/0.terrain").status, 404);
  EXPECT_EQ(http_get(port, "/surf/1/0/0.png?encoding=lerc").status, 400);
  EXPECT_EQ(server.stop(), 0) << "SIGTERM should end it cleanly";
}

// MVT of line and point packages equal the exports' tiles; style.json and
// TileJSON point at this server.
TEST(Serve, VectorTilesAndStylesPointAtTheServer) {
  TempDir dir("serve-vectors");
  const fs::path& v = vector_packages();
  ASSERT_TRUE(run_all({vectorize() + " export -q " + (v / "roads.mbtiles").string() + " -o " +
                           (dir / "roads").string(),
                       vectorize() + " export -q " + (v / "towns.mbtiles").string() + " -o " +
                           (dir / "towns").string()},
                      dir.path()));
  ServeProcess server({(v / "roads.mbtiles").string(), (v / "towns.mbtiles").string()}, dir.path());
  ASSERT_GT(server.port(), 0) << server.log();
  const int port = server.port();
  const std::string base = "http://127.0.0.1:" + std::to_string(port);
  for (const std::string name : {"roads", "towns"}) {
    size_t tiles = 0;
    for (const auto& e : fs::recursive_directory_iterator(dir / name)) {
      if (e.path().extension() != ".pbf") continue;
      const std::string rel = fs::relative(e.path(), dir / name).string();
      const HttpReply r = http_get(port, "/" + name + "/" + rel, "Accept-Encoding: gzip\r\n");
      ASSERT_EQ(r.status, 200) << name << "/" << rel;
      EXPECT_EQ(r.header("content-type"), "application/vnd.mapbox-vector-tile");
      EXPECT_EQ(r.header("content-encoding"), "gzip");
      EXPECT_TRUE(gunzip(r.body) == gunzip(read_file(e.path()))) << name << "/" << rel;
      ++tiles;
    }
    EXPECT_GT(tiles, 3u) << name;
    const auto tj = tileformat::JsonValue::parse(http_get(port, "/" + name + ".json").body);
    EXPECT_EQ(tj.find("tilejson")->string(), "3.0.0");
    EXPECT_EQ(tj.find("tiles")->array().at(0).string(), base + "/" + name + "/{z}/{x}/{y}.pbf");
    const auto style =
        tileformat::JsonValue::parse(http_get(port, "/" + name + "/style.json").body);
    EXPECT_EQ(style.find("version")->number(), 8);
    const auto& sources = style.find("sources")->members();
    ASSERT_EQ(sources.size(), 1u);
    EXPECT_EQ(sources[0].second.find("url")->string(), base + "/" + name + ".json");
  }
  // A tile inside the pyramid with nothing in it: 204.
  EXPECT_EQ(http_get(port, "/roads/8/0/0.pbf").status, 204);
}

// Line and point tiles drawn as images for CesiumJS (/NAME/z/x/y.png, issue
// 55 part 3), checked against positions worked out here from the web
// mercator formulas (and the geodetic tiling's, for a geodetic package): the line's pixels in its
// style's colour and width (4 px: opaque on it, clear 6 px away), the place a disc of 3 px in
// #d7301f at 0.8 with a white rim; a tile with nothing is transparent.
TEST(Serve, LineAndPointTilesAsImagesDrawWhatTheStylesSay) {
  TempDir dir("serve-raster");
  std::ofstream(dir / "line.geojson")
      << R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},)"
      << R"("geometry":{"type":"LineString","coordinates":[[7.0,46.0],[8.0,47.0]]}}]})";
  std::ofstream(dir / "place.csv") << "lon,lat,v\n7.3,46.3,1\n";
  ASSERT_TRUE(
      run_all({vectorize() + " lines -q " + (dir / "line.geojson").string() +
                   " --max-zoom 8 --style 'line:color=#ff0000,width=4px' -o " +
                   (dir / "line.mbtiles").string(),
               vectorize() + " points -q " + (dir / "place.csv").string() +
                   " --xy lon,lat --fields v --max-zoom 8 -o " + (dir / "place.mbtiles").string()},
              dir.path()));
  ServeProcess server({(dir / "line.mbtiles").string(), (dir / "place.mbtiles").string()},
                      dir.path());
  ASSERT_GT(server.port(), 0) << server.log();
  // Global pixel of (lon, lat) at zoom 8 (256 px tiles).
  auto pixel = [](double lon, double lat) {
    const double n = 256.0 * 256;
    return std::pair{
        (lon + 180) / 360 * n,
        (1 - std::asinh(std::tan(lat * std::acos(-1.0) / 180)) / std::acos(-1.0)) / 2 * n};
  };
  auto tile_of = [&](const std::string& name, double gx, double gy, int& w, int& h) {
    const HttpReply r = http_get(server.port(), "/" + name + "/8/" + std::to_string(int(gx / 256)) +
                                                    "/" + std::to_string(int(gy / 256)) + ".png");
    EXPECT_EQ(r.status, 200) << r.body;
    EXPECT_EQ(r.header("content-type"), "image/png");
    return png_pixels(r.body, w, h, 4);
  };
  int w = 0, h = 0;
  // The line's midpoint in its tile, and 6 px off it across (the line runs
  // north-east, so across is about (1, 1) / sqrt 2 in pixels).
  const auto [mx, my] = pixel(7.5, 46.5);
  const auto line = tile_of("line", mx, my, w, h);
  ASSERT_EQ(line.size(), size_t(256) * 256 * 4);
  auto at = [&](const std::vector<uint8_t>& px, double gx, double gy) {
    const size_t i = (size_t(int(gy) % 256) * 256 + size_t(int(gx) % 256)) * 4;
    return std::vector<int>{px[i], px[i + 1], px[i + 2], px[i + 3]};
  };
  EXPECT_EQ(at(line, mx, my), (std::vector<int>{255, 0, 0, 255}));
  EXPECT_EQ(at(line, mx + 6 / std::sqrt(2.0), my + 6 / std::sqrt(2.0))[3], 0);
  EXPECT_EQ(at(line, mx - 6 / std::sqrt(2.0), my - 6 / std::sqrt(2.0))[3], 0);
  // The place: its centre red at 0.8, 3.5 px out the white rim, 6 px out clear.
  const auto [px, py] = pixel(7.3, 46.3);
  const auto place = tile_of("place", px, py, w, h);
  ASSERT_EQ(place.size(), size_t(256) * 256 * 4);
  const auto centre = at(place, px, py);
  EXPECT_NEAR(centre[0], 0xd7, 2);
  EXPECT_NEAR(centre[1], 0x30, 2);
  EXPECT_NEAR(centre[3], 204, 2);
  const auto rim = at(place, px + 3.6, py);
  EXPECT_GT(rim[1], 200) << "white rim";
  EXPECT_GT(rim[3], 100);
  EXPECT_EQ(at(place, px + 6.5, py)[3], 0);
  // The same line in the geodetic tiling (CesiumJS's geographic scheme):
  // 2 x 1 tiles at zoom 0, so at zoom 7 a pixel is 180 / 2^7 / 256 degrees.
  ASSERT_TRUE(run_all(
      {vectorize() + " lines -q --tiling geodetic " + (dir / "line.geojson").string() +
       " --max-zoom 7 --style 'line:color=#ff0000,width=4px' -o " + (dir / "geo.mbtiles").string()},
      dir.path()));
  ServeProcess geo_server({(dir / "geo.mbtiles").string()}, dir.path());
  ASSERT_GT(geo_server.port(), 0) << geo_server.log();
  const double deg_per_px = 180.0 / 128 / 256;
  const double gx = (7.5 + 180) / deg_per_px, gy = (90 - 46.5) / deg_per_px;
  const HttpReply geo_tile =
      http_get(geo_server.port(), "/geo/7/" + std::to_string(int(gx / 256)) + "/" +
                                      std::to_string(int(gy / 256)) + ".png");
  ASSERT_EQ(geo_tile.status, 200) << geo_tile.body;
  const auto geo = png_pixels(geo_tile.body, w, h, 4);
  ASSERT_EQ(geo.size(), size_t(256) * 256 * 4);
  EXPECT_EQ(at(geo, gx, gy), (std::vector<int>{255, 0, 0, 255}));
  // (In degrees the line runs at 45 degrees: across is (1, 1) / sqrt 2 too.)
  EXPECT_EQ(at(geo, gx + 6 / std::sqrt(2.0), gy + 6 / std::sqrt(2.0))[3], 0);
  // A tile of the pyramid with nothing in it: transparent, not a 204.
  const HttpReply empty = http_get(server.port(), "/line/8/0/0.png");
  EXPECT_EQ(empty.status, 200);
  const auto clear = png_pixels(empty.body, w, h, 4);
  ASSERT_FALSE(clear.empty());
  EXPECT_EQ(*std::max_element(clear.begin(), clear.end()), 0);
}

// An area package served as line packages are: nc.gpkg's 100 counties as a
// choropleth of BIR74 in 4 classes. Every .pbf the export writes is served
// with the same bytes (gzip); the TileJSON lists the layer's fields; the
// style fills by a step over the package's breaks; GDAL's MVT driver reads a
// served tile's polygons with the county's attributes, its value and class;
// the tile drawn as a PNG has the class colour at 0.8 inside each of 4
// counties (one per class, the classes computed here from BIR74 and the
// breaks `info --json` lists) and nothing outside the state.
TEST(Serve, AreaChoroplethTilesTileJsonStyleAndImages) {
  TempDir dir("serve-areas");
  const std::string pkg = (dir / "nc.mbtiles").string();
  ASSERT_TRUE(run_all({vectorize() + " areas -q " + sample("nc.gpkg").string() +
                           " --choropleth BIR74 --classes 4 --max-zoom 7 -o " + pkg,
                       vectorize() + " export -q " + pkg + " -o " + (dir / "nc").string()},
                      dir.path()));
  const std::vector<ChoroplethClass> classes = choropleth_classes(pkg, dir.path());
  ASSERT_EQ(classes.size(), 4u);
  ServeProcess server({pkg}, dir.path());
  ASSERT_GT(server.port(), 0) << server.log();
  const int port = server.port();
  const std::string base = "http://127.0.0.1:" + std::to_string(port);

  // The export's tiles, byte for byte.
  size_t tiles = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir / "nc")) {
    if (e.path().extension() != ".pbf") continue;
    const std::string rel = fs::relative(e.path(), dir / "nc").string();
    const HttpReply r = http_get(port, "/nc/" + rel, "Accept-Encoding: gzip\r\n");
    ASSERT_EQ(r.status, 200) << rel;
    EXPECT_EQ(r.header("content-type"), "application/vnd.mapbox-vector-tile");
    EXPECT_EQ(r.header("content-encoding"), "gzip");
    EXPECT_TRUE(gunzip(r.body) == gunzip(read_file(e.path()))) << rel;
    ++tiles;
  }
  EXPECT_GT(tiles, 10u);
  EXPECT_EQ(http_get(port, "/nc/7/0/0.pbf").status, 204);

  // TileJSON: the tiles here, the layer and its fields.
  const auto tj = tileformat::JsonValue::parse(http_get(port, "/nc.json").body);
  EXPECT_EQ(tj.find("tilejson")->string(), "3.0.0");
  EXPECT_EQ(tj.find("tiles")->array().at(0).string(), base + "/nc/{z}/{x}/{y}.pbf");
  EXPECT_EQ(tj.find("maxzoom")->number(), 7);
  const auto& layers = tj.find("vector_layers")->array();
  ASSERT_EQ(layers.size(), 1u);
  EXPECT_EQ(layers[0].find("id")->string(), "nc.gpkg");
  const auto* fields = layers[0].find("fields");
  ASSERT_TRUE(fields);
  EXPECT_EQ(fields->find("NAME")->string(), "String");
  EXPECT_EQ(fields->find("BIR74")->string(), "Number");
  EXPECT_EQ(fields->find("value")->string(), "Number");
  EXPECT_EQ(fields->find("class")->string(), "Number");

  // The style: its source the TileJSON, the choropleth's fill a step over the
  // breaks, the outlines over it.
  const auto style = tileformat::JsonValue::parse(http_get(port, "/nc/style.json").body);
  EXPECT_EQ(style.find("version")->number(), 8);
  const auto& sources = style.find("sources")->members();
  ASSERT_EQ(sources.size(), 1u);
  EXPECT_EQ(sources[0].second.find("url")->string(), base + "/nc.json");
  const tileformat::JsonValue* fill = nullptr;
  std::vector<std::string> types;
  for (const auto& l : style.find("layers")->array()) {
    types.push_back(l.find("type")->string());
    if (l.find("id")->string() == "nc.gpkg/choropleth") fill = &l;
  }
  EXPECT_EQ(types, (std::vector<std::string>{"fill", "fill", "line"}));
  ASSERT_TRUE(fill) << "no choropleth fill layer";
  EXPECT_EQ(fill->find("type")->string(), "fill");
  EXPECT_EQ(fill->find("source-layer")->string(), "nc.gpkg");
  const auto& step = fill->find("paint")->find("fill-color")->array();
  ASSERT_EQ(step.size(), 3 + 2 * (classes.size() - 1));
  EXPECT_EQ(step[0].string(), "step");
  EXPECT_EQ(step[2].string(), classes[0].color);
  for (size_t i = 1; i < classes.size(); ++i) {
    EXPECT_EQ(step[1 + 2 * i].number(), classes[i].min);
    EXPECT_EQ(step[2 + 2 * i].string(), classes[i].color);
  }
  EXPECT_EQ(fill->find("paint")->find("fill-opacity")->number(), 0.8);
  EXPECT_NE(http_get(port, "/").body.find("/nc/style.json"), std::string::npos);

  // One county per class, the one farthest inside its border.
  std::vector<County> picked(classes.size() + 1);
  for (const County& c : nc_counties()) {
    const int k = class_of(classes, c.births);
    ASSERT_GT(k, 0) << c.name << " " << c.births;
    if (c.clearance > picked[k].clearance) picked[k] = c;
  }
  constexpr double kPi = 3.14159265358979323846, kR = 6378137;
  const int z = 7;
  const double world = 256.0 * (1 << z);
  for (int k = 1; k <= int(classes.size()); ++k) {
    const County& c = picked[size_t(k)];
    ASSERT_GT(c.clearance * world / 360, 6) << "class " << k << ": " << c.name;
    const double gx = (c.lon + 180) / 360 * world,
                 gy = (1 - std::asinh(std::tan(c.lat * kPi / 180)) / kPi) / 2 * world;
    const std::string tile = "/nc/" + std::to_string(z) + "/" + std::to_string(int(gx / 256)) +
                             "/" + std::to_string(int(gy / 256));
    SCOPED_TRACE(c.name + " (BIR74 " + std::to_string(c.births) + ", class " + std::to_string(k) +
                 ") in " + tile);
    // The vector tile, read by GDAL's MVT driver: the county's polygon holds
    // the point, with its attributes, value and class.
    const HttpReply pbf = http_get(port, tile + ".pbf", "Accept-Encoding: gzip\r\n");
    ASSERT_EQ(pbf.status, 200);
    EXPECT_EQ(pbf.header("content-encoding"), "gzip");
    const fs::path file = dir / ("tile" + std::to_string(k) + ".pbf");
    std::ofstream(file, std::ios::binary) << gunzip(pbf.body);
    const std::string ox = "X=" + std::to_string(int(gx / 256)),
                      oy = "Y=" + std::to_string(int(gy / 256)), oz = "Z=" + std::to_string(z);
    const char* options[] = {ox.c_str(), oy.c_str(), oz.c_str(), "METADATA_FILE=", nullptr};
    const char* drivers[] = {"MVT", nullptr};
    GDALDatasetH ds = GDALOpenEx(file.c_str(), GDAL_OF_VECTOR, drivers, options, nullptr);
    ASSERT_TRUE(ds) << "GDAL's MVT driver cannot open " << tile;
    ASSERT_EQ(GDALDatasetGetLayerCount(ds), 1);
    OGRLayerH layer = GDALDatasetGetLayer(ds, 0);
    EXPECT_STREQ(OGR_L_GetName(layer), "nc.gpkg");
    OGRGeometryH at = OGR_G_CreateGeometry(wkbPoint);
    OGR_G_SetPoint_2D(at, 0, c.lon * kPi / 180 * kR, kR * std::asinh(std::tan(c.lat * kPi / 180)));
    int holding = 0, features = 0;
    OGR_L_ResetReading(layer);
    while (OGRFeatureH f = OGR_L_GetNextFeature(layer)) {
      ++features;
      OGRGeometryH g = OGR_F_GetGeometryRef(f);
      ASSERT_TRUE(g);
      const OGRwkbGeometryType type = wkbFlatten(OGR_G_GetGeometryType(g));
      EXPECT_TRUE(type == wkbPolygon || type == wkbMultiPolygon) << OGRGeometryTypeToName(type);
      EXPECT_GE(OGR_F_GetFieldIndex(f, "value"), 0);
      if (!OGR_G_Contains(g, at)) {
        OGR_F_Destroy(f);
        continue;
      }
      ++holding;
      EXPECT_STREQ(OGR_F_GetFieldAsString(f, OGR_F_GetFieldIndex(f, "NAME")), c.name.c_str());
      EXPECT_EQ(OGR_F_GetFieldAsDouble(f, OGR_F_GetFieldIndex(f, "BIR74")), c.births);
      const int value = OGR_F_GetFieldIndex(f, "value");
      ASSERT_GE(value, 0);
      EXPECT_TRUE(OGR_F_IsFieldSetAndNotNull(f, value));
      EXPECT_EQ(OGR_F_GetFieldAsDouble(f, value), c.births);
      EXPECT_EQ(OGR_F_GetFieldAsInteger(f, OGR_F_GetFieldIndex(f, "class")), k);
      OGR_F_Destroy(f);
    }
    OGR_G_DestroyGeometry(at);
    GDALClose(ds);
    EXPECT_GT(features, 1);
    EXPECT_EQ(holding, 1);
    // The tile drawn: the class colour at the style's opacity, 0.8.
    const HttpReply png = http_get(port, tile + ".png");
    ASSERT_EQ(png.status, 200);
    EXPECT_EQ(png.header("content-type"), "image/png");
    int w = 0, h = 0;
    const auto px = png_pixels(png.body, w, h, 4);
    ASSERT_EQ(px.size(), size_t(256) * 256 * 4);
    const size_t i = (size_t(int(gy) % 256) * 256 + size_t(int(gx) % 256)) * 4;
    const std::vector<int> expected = rgb_of(classes[size_t(k - 1)].color);
    for (int b = 0; b < 3; ++b)
      EXPECT_NEAR(px[i + b], expected[size_t(b)], 1) << "band " << b;
    EXPECT_NEAR(px[i + 3], 204, 1);
  }
  // Outside the state, in a tile that holds part of it: South Carolina and
  // the Atlantic at zoom 5 transparent, the state drawn.
  for (const auto& [lon, lat] : {std::pair{-80.5, 33.2}, std::pair{-74.5, 35.0}}) {
    const double w5 = 256.0 * 32, gx = (lon + 180) / 360 * w5,
                 gy = (1 - std::asinh(std::tan(lat * kPi / 180)) / kPi) / 2 * w5;
    const HttpReply png = http_get(port, "/nc/5/" + std::to_string(int(gx / 256)) + "/" +
                                             std::to_string(int(gy / 256)) + ".png");
    ASSERT_EQ(png.status, 200);
    int w = 0, h = 0;
    const auto px = png_pixels(png.body, w, h, 4);
    ASSERT_EQ(px.size(), size_t(256) * 256 * 4);
    EXPECT_EQ(px[(size_t(int(gy) % 256) * 256 + size_t(int(gx) % 256)) * 4 + 3], 0)
        << lon << "," << lat;
    size_t drawn = 0;
    for (size_t j = 3; j < px.size(); j += 4)
      drawn += px[j] > 0;
    EXPECT_GT(drawn, 1000u) << "the state in tile of " << lon << "," << lat;
  }
}

// A polygon with a hole in the geodetic tiling and a style class of its own
// (#00ff00 at 0.5, times 0.8 on web maps): drawn for CesiumJS, filled by the
// winding rule (the ring green at 0.4, the hole and the outside clear); MVT refused as for lines
// (web maps read web mercator only); the style fills the class.
TEST(Serve, AreaImagesFillByTheWindingRuleGeodeticToo) {
  TempDir dir("serve-area-hole");
  std::ofstream(dir / "sq.geojson")
      << R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"kind":"park"},)"
      << R"("geometry":{"type":"Polygon","coordinates":[[[7,46],[9,46],[9,48],[7,48],[7,46]],)"
      << R"([[7.5,46.5],[7.5,47.5],[8.5,47.5],[8.5,46.5],[7.5,46.5]]]}}]})";
  ASSERT_TRUE(
      run_all({vectorize() + " areas -q --tiling geodetic " + (dir / "sq.geojson").string() +
               " --class-field kind --style 'park:color=#00ff00,opacity=0.5' --max-zoom 6 " +
               "-o " + (dir / "sq.mbtiles").string()},
              dir.path()));
  ServeProcess server({(dir / "sq.mbtiles").string()}, dir.path());
  ASSERT_GT(server.port(), 0) << server.log();
  const int port = server.port();
  // Geodetic zoom 6: 128 x 64 tiles of 180 / 64 degrees.
  const double deg_per_px = 180.0 / 64 / 256;
  auto alpha_and_rgb = [&](double lon, double lat) {
    const double gx = (lon + 180) / deg_per_px, gy = (90 - lat) / deg_per_px;
    const HttpReply r = http_get(port, "/sq/6/" + std::to_string(int(gx / 256)) + "/" +
                                           std::to_string(int(gy / 256)) + ".png");
    EXPECT_EQ(r.status, 200) << r.body;
    int w = 0, h = 0;
    const auto px = png_pixels(r.body, w, h, 4);
    if (px.size() != size_t(256) * 256 * 4) return std::vector<int>{-1, -1, -1, -1};
    const size_t i = (size_t(int(gy) % 256) * 256 + size_t(int(gx) % 256)) * 4;
    return std::vector<int>{px[i + 3], px[i], px[i + 1], px[i + 2]};
  };
  // The class's opacity 0.5 times the web maps' fill opacity 0.8: 0.4.
  const auto ring = alpha_and_rgb(7.25, 47.0);
  EXPECT_NEAR(ring[0], 102, 1);
  EXPECT_EQ(std::vector<int>(ring.begin() + 1, ring.end()), (std::vector<int>{0, 255, 0}));
  EXPECT_EQ(alpha_and_rgb(8.0, 47.0)[0], 0) << "the hole";
  EXPECT_EQ(alpha_and_rgb(7.25, 45.5)[0], 0) << "outside";
  EXPECT_NEAR(alpha_and_rgb(8.75, 46.25)[0], 102, 1) << "the ring's other corner";
  const HttpReply pbf = http_get(port, "/sq/6/66/15.pbf");
  EXPECT_EQ(pbf.status, 404);
  EXPECT_NE(pbf.body.find("webmercator"), std::string::npos) << pbf.body;
  const auto style = tileformat::JsonValue::parse(http_get(port, "/sq/style.json").body);
  const auto& first = style.find("layers")->array().at(0);
  EXPECT_EQ(first.find("type")->string(), "fill");
  EXPECT_EQ(first.find("paint")->find("fill-color")->string(), "#00ff00");
  EXPECT_NEAR(first.find("paint")->find("fill-opacity")->number(), 0.4, 1e-9);
  const auto tj = tileformat::JsonValue::parse(http_get(port, "/sq.json").body);
  EXPECT_EQ(tj.find("vector_layers")->array().at(0).find("fields")->find("kind")->string(),
            "String");
}

namespace {

// A MapLibre glyph PBF as this test reads it, written from the message
// MapLibre documents (glyphs { repeated fontstack stacks = 1 }, fontstack
// { name = 1, range = 2, repeated glyph glyphs = 3 }, glyph { id = 1,
// bitmap = 2, width = 3, height = 4, left = 5 (sint32), top = 6 (sint32),
// advance = 7 }) over the protobuf wire format alone: no code shared with
// the server's writer. Throws std::runtime_error on anything malformed.
struct PbfGlyph {
  uint32_t id = 0, width = 0, height = 0, advance = 0;
  int32_t left = 0, top = 0;
  size_t bitmap = 0;  // bytes
};
struct PbfFontstack {
  std::string name, range;
  std::vector<PbfGlyph> glyphs;
};

class WireReader {
 public:
  explicit WireReader(std::string_view bytes) : in_(bytes) {}
  bool done() const { return at_ == in_.size(); }
  uint64_t varint() {
    uint64_t v = 0;
    for (int shift = 0; shift < 64; shift += 7) {
      if (at_ >= in_.size()) throw std::runtime_error("a varint runs past the end");
      const uint8_t b = uint8_t(in_[at_++]);
      v |= uint64_t(b & 0x7f) << shift;
      if (!(b & 0x80)) return v;
    }
    throw std::runtime_error("a varint longer than 10 bytes");
  }
  // The next field's number and wire type.
  std::pair<uint32_t, int> key() {
    const uint64_t k = varint();
    return {uint32_t(k >> 3), int(k & 7)};
  }
  std::string_view bytes() {
    const uint64_t n = varint();
    if (n > in_.size() - at_) throw std::runtime_error("a length past the end");
    const std::string_view out = in_.substr(at_, size_t(n));
    at_ += size_t(n);
    return out;
  }
  void skip(int wire) {
    if (wire == 0) {
      varint();
    } else if (wire == 2) {
      bytes();
    } else if (wire == 1 || wire == 5) {
      const size_t n = wire == 1 ? 8 : 4;
      if (n > in_.size() - at_) throw std::runtime_error("a fixed field past the end");
      at_ += n;
    } else {
      throw std::runtime_error("wire type " + std::to_string(wire));
    }
  }

 private:
  std::string_view in_;
  size_t at_ = 0;
};

int32_t unzigzag(uint64_t v) {
  return int32_t(uint32_t(v >> 1) ^ (~uint32_t(v & 1) + 1));
}

std::vector<PbfFontstack> decode_glyph_pbf(std::string_view data) {
  std::vector<PbfFontstack> out;
  WireReader top(data);
  while (!top.done()) {
    const auto [field, wire] = top.key();
    if (field != 1 || wire != 2) {
      top.skip(wire);
      continue;
    }
    PbfFontstack stack;
    WireReader fs(top.bytes());
    while (!fs.done()) {
      const auto [f, w] = fs.key();
      if (f == 1 && w == 2) {
        stack.name = std::string(fs.bytes());
      } else if (f == 2 && w == 2) {
        stack.range = std::string(fs.bytes());
      } else if (f == 3 && w == 2) {
        PbfGlyph g;
        WireReader gr(fs.bytes());
        while (!gr.done()) {
          const auto [gf, gw] = gr.key();
          if (gf == 2 && gw == 2) {
            g.bitmap = gr.bytes().size();
          } else if (gw == 0 && gf >= 1 && gf <= 7) {
            const uint64_t v = gr.varint();
            if (gf == 1) g.id = uint32_t(v);
            if (gf == 3) g.width = uint32_t(v);
            if (gf == 4) g.height = uint32_t(v);
            if (gf == 5) g.left = unzigzag(v);
            if (gf == 6) g.top = unzigzag(v);
            if (gf == 7) g.advance = uint32_t(v);
          } else {
            gr.skip(gw);
          }
        }
        stack.glyphs.push_back(g);
      } else {
        fs.skip(w);
      }
    }
    out.push_back(std::move(stack));
  }
  return out;
}

// A URL path segment with spaces and other reserved bytes percent-encoded.
std::string path_escape(const std::string& s) {
  std::string out;
  for (const unsigned char c : s) {
    if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~') {
      out += char(c);
    } else {
      char hex[4];
      std::snprintf(hex, sizeof hex, "%%%02X", c);
      out += hex;
    }
  }
  return out;
}

}  // namespace

// nc.gpkg's counties labelled by NAME, served: every tile the export writes
// (names and label points included) is served byte for byte; the TileJSON
// lists `name` and the `labels` layer; the style's glyphs are this server's
// /fonts and its symbol layer names their fontstack. That URL answers range
// 0-255 with a PBF (application/x-protobuf, cacheable, gzipped on request)
// decoded here by a reader of the protobuf wire format written in this test:
// one fontstack of that name and range, Latin letters with SDF bitmaps of
// (width + 6) x (height + 6) bytes, the same bytes as the export's
// fonts/FONTSTACK/0-255.pbf; a range that is not START-END (START a multiple
// of 256 in the BMP, END = START + 255), a range no font covers and another
// fontstack are 404.
TEST(Serve, LabelledAreasGetNamesAStyleWithLabelsAndTheirGlyphs) {
  TempDir dir("serve-labels");
  const std::string pkg = (dir / "nc.mbtiles").string();
  ASSERT_TRUE(run_all({vectorize() + " areas -q " + sample("nc.gpkg").string() +
                           " --label-field NAME --max-zoom 6 -o " + pkg,
                       vectorize() + " export -q " + pkg + " -o " + (dir / "nc").string() +
                           " --style-json " + (dir / "style.json").string()},
                      dir.path()));
  ServeProcess server({pkg}, dir.path());
  ASSERT_GT(server.port(), 0) << server.log();
  const int port = server.port();
  const std::string base = "http://127.0.0.1:" + std::to_string(port);
  size_t tiles = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir / "nc")) {
    if (e.path().extension() != ".pbf") continue;
    const std::string rel = fs::relative(e.path(), dir / "nc").string();
    const HttpReply r = http_get(port, "/nc/" + rel, "Accept-Encoding: gzip\r\n");
    ASSERT_EQ(r.status, 200) << rel;
    EXPECT_TRUE(gunzip(r.body) == gunzip(read_file(e.path()))) << rel;
    ++tiles;
  }
  EXPECT_GT(tiles, 10u);
  const auto tj = tileformat::JsonValue::parse(http_get(port, "/nc.json").body);
  std::map<std::string, std::string> name_type;
  for (const auto& l : tj.find("vector_layers")->array())
    name_type[l.find("id")->string()] = l.find("fields")->find("name")->string();
  EXPECT_EQ(name_type,
            (std::map<std::string, std::string>{{"labels", "String"}, {"nc.gpkg", "String"}}));

  const auto style = tileformat::JsonValue::parse(http_get(port, "/nc/style.json").body);
  ASSERT_TRUE(style.find("glyphs"));
  const std::string glyphs = style.find("glyphs")->string();
  EXPECT_EQ(glyphs, base + "/fonts/{fontstack}/{range}.pbf");
  const tileformat::JsonValue* symbols = nullptr;
  for (const auto& l : style.find("layers")->array())
    if (l.find("type")->string() == "symbol") symbols = &l;
  ASSERT_TRUE(symbols);
  EXPECT_EQ(symbols->find("source-layer")->string(), "labels");
  const std::string font = symbols->find("layout")->find("text-font")->array().at(0).string();
  ASSERT_FALSE(font.empty());

  const std::string fonts = "/fonts/" + path_escape(font) + "/";
  const HttpReply latin = http_get(port, fonts + "0-255.pbf");
  ASSERT_EQ(latin.status, 200) << latin.body;
  EXPECT_EQ(latin.header("content-type"), "application/x-protobuf");
  EXPECT_NE(latin.header("cache-control").find("max-age="), std::string::npos);
  EXPECT_FALSE(latin.header("etag").empty());
  EXPECT_TRUE(latin.body == read_file(dir / "fonts" / font / "0-255.pbf"))
      << "the export's glyphs and the server's differ";
  std::vector<PbfFontstack> stacks;
  ASSERT_NO_THROW(stacks = decode_glyph_pbf(latin.body));
  ASSERT_EQ(stacks.size(), 1u);
  EXPECT_EQ(stacks[0].name, font);
  EXPECT_EQ(stacks[0].range, "0-255");
  std::map<uint32_t, PbfGlyph> by_id;
  for (const PbfGlyph& g : stacks[0].glyphs) {
    EXPECT_LE(g.id, 255u);
    if (g.width > 0) {
      EXPECT_EQ(g.bitmap, size_t(g.width + 6) * (g.height + 6)) << g.id;
    }
    by_id[g.id] = g;
  }
  for (const char32_t c : U"AZaz09 ") {
    if (!c) continue;
    ASSERT_TRUE(by_id.count(c)) << "code point " << uint32_t(c);
    EXPECT_GT(by_id[c].advance, 0u) << uint32_t(c);
  }
  EXPECT_GT(by_id[U'A'].bitmap, 0u);
  EXPECT_EQ(by_id[U' '].bitmap, 0u);
  const HttpReply zipped = http_get(port, fonts + "0-255.pbf", "Accept-Encoding: gzip\r\n");
  EXPECT_EQ(zipped.header("content-encoding"), "gzip");
  EXPECT_TRUE(gunzip(zipped.body) == latin.body);
  const HttpReply arabic = http_get(port, fonts + "1536-1791.pbf");
  EXPECT_EQ(arabic.status, 200);
  ASSERT_NO_THROW(stacks = decode_glyph_pbf(arabic.body));
  EXPECT_EQ(stacks.at(0).range, "1536-1791");
  for (const char* bad :
       {"1-256", "0-254", "256-767", "00-255", "abc", "-0-255", "65536-65791", "55296-55551"})
    EXPECT_EQ(http_get(port, fonts + bad + ".pbf").status, 404) << bad;
  EXPECT_EQ(http_get(port, fonts + "0-255.png").status, 404);
  EXPECT_EQ(http_get(port, "/fonts/Arial%20Unicode%20MS%20Regular/0-255.pbf").status, 404);
  EXPECT_EQ(http_get(port, "/fonts/" + path_escape(font) + "/0-255").status, 404);
  EXPECT_EQ(http_get(port, "/fonts/" + path_escape(font)).status, 404);
  EXPECT_EQ(http_get(port, "/fonts/../0-255.pbf").status, 400);
  EXPECT_EQ(http_get(port, "/nc/style.json").status, 200) << "still serving";
}

// The HTTP contract: ETag and 304, CORS and preflight, methods, PMTiles
// ranges (206, 416), the preview pages and the libraries under /lib.
TEST(Serve, HttpContractEtagCorsRangesPages) {
  TempDir dir("serve-http");
  const fs::path pkg = dir / "surf.mbtiles";
  fs::copy_file(surface_dem() / "geodetic.mbtiles", pkg);
  ASSERT_TRUE(run_all({tiler() + " export -q " + pkg.string() + " --format terrarium -o " +
                       (dir / "dem.pmtiles").string()},
                      dir.path()));
  fs::create_directories(dir / "libs" / "demo");
  std::ofstream(dir / "libs" / "demo" / "lib.js") << "export const x = 1;\n";
  std::ofstream(dir / "secret.txt") << "not to be served\n";
  fs::create_symlink(dir / "secret.txt", dir / "libs" / "demo" / "escape.js");
  ServeProcess server(
      {pkg.string(), (dir / "dem.pmtiles").string(), "--web-libs", (dir / "libs").string()},
      dir.path());
  ASSERT_GT(server.port(), 0) << server.log();
  const int port = server.port();

  const HttpReply tile = http_get(port, "/surf/0/1/0.terrain");
  ASSERT_EQ(tile.status, 200);
  EXPECT_EQ(tile.header("access-control-allow-origin"), "*");
  const std::string etag = tile.header("etag");
  ASSERT_FALSE(etag.empty());
  EXPECT_FALSE(tile.header("cache-control").empty());
  const HttpReply again = http_get(port, "/surf/0/1/0.terrain", "If-None-Match: " + etag + "\r\n");
  EXPECT_EQ(again.status, 304);
  EXPECT_TRUE(again.body.empty());
  const HttpReply pre = http_get(port, "/surf/0/1/0.terrain", "", "OPTIONS");
  EXPECT_EQ(pre.status, 204);
  EXPECT_NE(pre.header("access-control-allow-methods").find("GET"), std::string::npos);
  EXPECT_EQ(http_get(port, "/surf/0/1/0.terrain", "", "POST").status, 405);
  const HttpReply head = http_get(port, "/surf/0/1/0.terrain", "", "HEAD");
  EXPECT_EQ(head.status, 200);
  EXPECT_EQ(head.header("content-length"), std::to_string(tile.body.size()));

  const std::string archive = read_file(dir / "dem.pmtiles");
  const HttpReply whole = http_get(port, "/dem.pmtiles");
  ASSERT_EQ(whole.status, 200);
  EXPECT_TRUE(whole.body == archive);
  const HttpReply part = http_get(port, "/dem.pmtiles", "Range: bytes=0-126\r\n");
  EXPECT_EQ(part.status, 206);
  EXPECT_EQ(part.header("content-range"), "bytes 0-126/" + std::to_string(archive.size()));
  EXPECT_TRUE(part.body == archive.substr(0, 127));
  const HttpReply tail = http_get(port, "/dem.pmtiles", "Range: bytes=-10\r\n");
  EXPECT_EQ(tail.status, 206);
  EXPECT_TRUE(tail.body == archive.substr(archive.size() - 10));
  EXPECT_EQ(http_get(port, "/dem.pmtiles",
                     "Range: bytes=" + std::to_string(archive.size() + 10) + "-\r\n")
                .status,
            416);

  const HttpReply index = http_get(port, "/");
  EXPECT_EQ(index.status, 200);
  EXPECT_NE(index.body.find("/view/cesium.html?pkg=surf"), std::string::npos);
  EXPECT_NE(index.body.find("/dem.pmtiles"), std::string::npos);
  EXPECT_EQ(http_get(port, "/view/maplibre.html").status, 200);
  EXPECT_EQ(http_get(port, "/lib/demo/lib.js").body, "export const x = 1;\n");
  EXPECT_EQ(http_get(port, "/lib/demo/lib.js").header("content-type"),
            "text/javascript; charset=utf-8");
  EXPECT_EQ(http_get(port, "/lib/demo/escape.js").status, 404) << "a symlink out of the libraries";
}

// The HTTP contract as the clients people use meet it (issue 55): the
// black-box checker tests/http_conformance/check_http.py, written from RFC
// 9110 without the server's code (and itself proven against nginx), runs
// its cases — ranges past the end, suffix and open ranges, 416, several
// ranges, If-Range, HEAD, If-None-Match lists, gzip once — over raw
// HTTP/1.1, curl, wget, Python urllib and GDAL's /vsicurl/ against every
// kind of answer: a PMTiles archive under pmtiles.js's 16 KiB first read
// and a large one, tiles cut on the fly and stored, MVT, JSON, pages and a
// library file.
TEST(Serve, ClientsPeopleUseGetRfc9110Answers) {
  TempDir dir("serve-rfc");
  const fs::path pkg = dir / "surf.mbtiles";
  fs::copy_file(surface_dem() / "geodetic.mbtiles", pkg);
  const fs::path& v = vector_packages();
  ASSERT_TRUE(
      run_all({tiler() + " export -q " + (surface_dem() / "mercator.mbtiles").string() +
                   " --format terrarium -o " + (dir / "dem.pmtiles").string(),
               vectorize() + " export -q " + (v / "roads.mbtiles").string() + " -o " +
                   (dir / "small.pmtiles").string(),
               "gdal_translate -q -ot Byte -scale " + (surface_dem() / "surface.tif").string() +
                   " " + (dir / "gray.tif").string(),
               tiler() + " imagery -q " + (dir / "gray.tif").string() + " --format png -o " +
                   (dir / "img.mbtiles").string()},
              dir.path()));
  ASSERT_LT(fs::file_size(dir / "small.pmtiles"), 16384u)
      << "must be under pmtiles.js's first read";
  fs::create_directories(dir / "libs" / "demo");
  std::ofstream(dir / "libs" / "demo" / "lib.js") << "export const x = 1;\n";
  ServeProcess server({pkg.string(), (dir / "dem.pmtiles").string(),
                       (dir / "small.pmtiles").string(), (dir / "img.mbtiles").string(),
                       (v / "roads.mbtiles").string(), "--web-libs", (dir / "libs").string()},
                      dir.path());
  ASSERT_GT(server.port(), 0) << server.log();
  const std::string base = "http://127.0.0.1:" + std::to_string(server.port());
  const std::string dem = "/dem.pmtiles=" + (dir / "dem.pmtiles").string();
  const std::string small = "/small.pmtiles=" + (dir / "small.pmtiles").string();
  const RunResult r =
      run("python3 " + globe_test::paths::source_dir() +
              "/tests/http_conformance/check_http.py --base " + base +
              " --timeout 10 --clients raw,curl,wget,urllib,gdal --gdalinfo /img/0/0/0.png" +
              " --gdal-read " + small + " --gdal-read " + dem + " " + small + " " + dem +
              " /surf.json /surf/layer.json /surf/0/1/0.terrain '/surf/0/1/0.terrain?extensions="
              "octvertexnormals' '/surf/0/0/0.png?encoding=terrarium' /img/0/0/0.png"
              " /roads/4/8/5.pbf /roads/style.json /roads.json / '/view/cesium.html?pkg=surf'"
              " /lib/demo/lib.js",
          dir.path());
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find(" passed, 0 failed"), std::string::npos) << r.out;
  std::cerr << "check_http.py: " << r.out.substr(r.out.rfind('\n', r.out.size() - 2) + 1);
  ASSERT_TRUE(server.alive()) << server.log();
}

// A hostile corpus against a running server: traversal in every spelling,
// overlong request lines and headers, bad ranges, huge and non-numeric
// coordinates, junk bytes, half-closed and silent connections. Nothing
// outside the packages is served, every answer is an error, the server
// stays up and still serves a valid tile.
TEST(Serve, HostileRequestsNeverTakeItDown) {
  TempDir dir("serve-hostile");
  const fs::path pkg = dir / "surf.mbtiles";
  fs::copy_file(surface_dem() / "geodetic.mbtiles", pkg);
  fs::create_directories(dir / "libs" / "x");
  std::ofstream(dir / "libs" / "x" / "a.js") << "1;\n";
  ServeProcess server(
      {pkg.string(), "--timeout", "1", "-j", "2", "--web-libs", (dir / "libs").string()},
      dir.path());
  ASSERT_GT(server.port(), 0) << server.log();
  const int port = server.port();
  const std::string host = "Host: 127.0.0.1\r\nConnection: close\r\n";
  const std::vector<std::string> targets = {"/lib/../../../../etc/passwd",
                                            "/lib/%2e%2e/%2e%2e/%2e%2e/etc/passwd",
                                            "/lib/x/%2e%2e%2f%2e%2e%2fetc%2fpasswd",
                                            "/..%2f..%2fetc%2fpasswd",
                                            "//etc/passwd",
                                            "/lib//etc/passwd",
                                            "/lib/x/..%5c..%5cetc%5cpasswd",
                                            "/surf/../../etc/passwd",
                                            "/%00/x",
                                            "/lib/x/a.js%00.png",
                                            "/etc/passwd",
                                            "/surf/1/0/0.terrain/../../../etc/passwd",
                                            "/surf/99999999999999999999/0/0.terrain",
                                            "/surf/-1/0/0.terrain",
                                            "/surf/1/0/-0.terrain",
                                            "/surf/1/0x1/0.terrain",
                                            "/surf/1/0/0.terrain.exe",
                                            "/surf.json/../surf.json",
                                            "/" + std::string(9000, 'a'),
                                            "http://evil.example/surf.json",
                                            "*"};
  for (const std::string& t : targets) {
    const std::string in = raw_exchange(port, "GET " + t + " HTTP/1.1\r\n" + host + "\r\n");
    const HttpReply r = parse_reply(in);
    EXPECT_TRUE(r.status == 0 || r.status >= 400) << t << " answered " << r.status;
    EXPECT_EQ(in.find("root:"), std::string::npos) << t << " served /etc/passwd";
  }
  const std::vector<std::string> raw = {
      "GET /surf/0/1/0.terrain?extensions=" + std::string(3000, 'x') + " HTTP/1.1\r\n" + host +
          "\r\n",
      "GET /surf/0/1/0.terrain HTTP/1.1\r\nHost: x\r\nX-Big: " + std::string(20000, 'b') +
          "\r\n\r\n",
      "GET /surf/0/1/0.terrain HTTP/1.1\r\nHost: x\r\nRange: bytes=99999999999999999999-\r\n"
      "Connection: close\r\n\r\n",
      "GET /surf/0/1/0.terrain HTTP/1.1\r\nHost: x\r\nRange: bytes=5-2,junk\r\nConnection: "
      "close\r\n\r\n",
      "\x16\x03\x01\x02\x00\x01\x00\x01\xfc\x03\x03garbage that looks like TLS\r\n\r\n",
      "GET /surf/0/1/0.terrain HTTP/9.9\r\n\r\n",
      "BREW /surf HTTP/1.1\r\nHost: x\r\n\r\n",
      "GET /surf/0/1/0.terrain HTTP/1.1\r\nHost: x\r\nContent-Length: 99999999999\r\n\r\nabc",
      std::string(100000, 'G'),
  };
  for (const std::string& r : raw) {
    const std::string in = raw_exchange(port, r, 4000);
    const HttpReply reply = parse_reply(in);
    EXPECT_NE(reply.status, 500) << r.substr(0, 60);
  }
  // Half-closed mid-request, and a client that never sends: both end.
  raw_exchange(port, "GET /surf/1/1/0.terr", 3000, true);
  const auto t0 = std::chrono::steady_clock::now();
  raw_exchange(port, "", 8000);
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(7))
      << "a silent client was not timed out (--timeout 1)";
  // Still alive, still serving.
  ASSERT_TRUE(server.alive()) << server.log();
  const HttpReply ok = http_get(port, "/surf/0/1/0.terrain");
  EXPECT_EQ(ok.status, 200);
  EXPECT_NO_THROW(spec_readers::quantized_mesh::decode(ok.body));
}

// A package replaced on disk (a rebuild renamed over it) is served from the
// new file; one that disappears is refused clearly (503) until it is back.
TEST(Serve, ReplacedPackagesArePickedUp) {
  TempDir dir("serve-replace");
  const fs::path pkg = dir / "surf.mbtiles";
  fs::copy_file(surface_dem() / "geodetic.mbtiles", pkg);
  ServeProcess server({pkg.string()}, dir.path());
  ASSERT_GT(server.port(), 0) << server.log();
  const int port = server.port();
  const HttpReply before = http_get(port, "/surf.json");
  ASSERT_EQ(before.status, 200);
  fs::copy_file(surface_dem() / "mercator.mbtiles", dir / "new.tmp");
  fs::rename(dir / "new.tmp", pkg);
  const HttpReply after = http_get(port, "/surf.json");
  ASSERT_EQ(after.status, 200);
  EXPECT_NE(after.body, before.body) << "still the old package";
  fs::rename(pkg, dir / "away.mbtiles");
  const HttpReply gone = http_get(port, "/surf.json");
  EXPECT_EQ(gone.status, 503);
  EXPECT_NE(gone.body.find("gone"), std::string::npos) << gone.body;
  fs::rename(dir / "away.mbtiles", pkg);
  EXPECT_EQ(http_get(port, "/surf.json").status, 200);
}

// Start-up errors: two inputs with one name, a missing file, a port in use.
TEST(Serve, RefusesDuplicateNamesMissingFilesAndBusyPorts) {
  TempDir dir("serve-cli");
  fs::create_directories(dir / "a");
  fs::copy_file(surface_dem() / "geodetic.mbtiles", dir / "surf.mbtiles");
  fs::copy_file(surface_dem() / "geodetic.mbtiles", dir / "a" / "surf.mbtiles");
  const RunResult dup = run(serve_path() + " " + (dir / "surf.mbtiles").string() + " " +
                                (dir / "a" / "surf.mbtiles").string(),
                            dir.path());
  EXPECT_EQ(dup.exit_code, 2) << dup.err;
  EXPECT_NE(dup.err.find("/surf"), std::string::npos) << dup.err;
  const RunResult missing = run(serve_path() + " " + (dir / "none.mbtiles").string(), dir.path());
  EXPECT_EQ(missing.exit_code, 1) << missing.err;
  EXPECT_NE(missing.err.find("none.mbtiles"), std::string::npos) << missing.err;
  ServeProcess first({(dir / "surf.mbtiles").string()}, dir.path());
  ASSERT_GT(first.port(), 0);
  // (`timeout`: a server that wrongly starts must not hang the test.)
  const RunResult busy = run("timeout 20 " + serve_path() + " " + (dir / "surf.mbtiles").string() +
                                 " --port " + std::to_string(first.port()),
                             dir.path());
  EXPECT_EQ(busy.exit_code, 3) << busy.err;
  EXPECT_NE(busy.err.find("cannot listen"), std::string::npos) << busy.err;
}

// Memory under load (issue 55): 100 clients at once ask every tile of the
// three finest zooms — none asked before — of a fresh server with 64 worker
// threads and --cache-mb 64. What the server comes to hold beyond its start
// is its caches and the tiles its cores are cutting (one per core at most,
// one heap per core), not a working set per thread: growth <= the cache +
// 128 MB. (The thread-per-connection server before grew by about 235 MB.)
// Every answer is a tile.
TEST(Serve, MemoryUnderOneHundredClientsIsTheCacheNotTheThreads) {
#ifdef GLOBE_ADDRESS_SANITIZER
  GTEST_SKIP() << "ASan's shadow memory and quarantine: the plain build checks the bound";
#endif
  TempDir dir("serve-memory");
  // 2048 x 1024 samples, 8 by 4 degrees: 165 tiles in the three finest zooms.
  const Surface wide{6, 14, 44, 48, 1.0 / 256, 800, 600, 2 * kPi / 3, 2 * kPi / 2};
  wide.write((dir / "wide.tif").string());
  ASSERT_TRUE(run_all({tiler() + " terrain -q " + (dir / "wide.tif").string() + " -o " +
                       (dir / "wide.mbtiles").string()},
                      dir.path()));
  ServeProcess server(
      {(dir / "wide.mbtiles").string(), "-j", "64", "--cache-mb", "64", "--timeout", "60"},
      dir.path());
  ASSERT_GT(server.port(), 0) << server.log();
  const int port = server.port();
  const HttpReply layer = http_get(port, "/wide/layer.json");
  ASSERT_EQ(layer.status, 200);
  const auto available = tileformat::JsonValue::parse(layer.body).find("available")->array();
  std::vector<std::string> targets;
  for (size_t z = available.size() - 3; z < available.size(); ++z)
    for (const auto& r : available[z].array())
      for (int x = int(r.find("startX")->number()); x <= int(r.find("endX")->number()); ++x)
        for (int y = int(r.find("startY")->number()); y <= int(r.find("endY")->number()); ++y)
          targets.push_back("/wide/" + std::to_string(z) + "/" + std::to_string(x) + "/" +
                            std::to_string(y) + ".terrain?extensions=octvertexnormals");
  ASSERT_GT(targets.size(), 100u);
  const double start_mb = server.memory_mb("VmRSS");
  constexpr int kClients = 100;
  std::atomic<int> wrong{0};
  std::vector<std::thread> clients;
  for (int c = 0; c < kClients; ++c)
    clients.emplace_back([&, c] {
      for (size_t i = size_t(c); i < targets.size(); i += kClients)
        if (http_get(port, targets[i], "", "GET", 60000).status != 200) ++wrong;
    });
  for (std::thread& t : clients)
    t.join();
  EXPECT_EQ(wrong, 0);
  const double peak_mb = server.memory_mb("VmHWM");
  std::cerr << targets.size() << " new tiles to " << kClients << " clients: RSS " << start_mb
            << " MB at start, " << peak_mb << " MB at the peak\n";
  EXPECT_LE(peak_mb - start_mb, 64 + 128) << "grew past its cache (--cache-mb 64) + 128 MB";
  ASSERT_TRUE(server.alive()) << server.log();
}

// A bounded load on 127.0.0.1: 200 clients at once, each fetching random
// tiles (quantized-mesh cut on the fly, MVT, raster-DEM) on its own
// connection, 1,000 requests in all; every answer is the right bytes.
// Latency and throughput are printed, not asserted (bench/serve.sh measures).
TEST(Serve, TwoHundredConcurrentClientsAllAnsweredCorrectly) {
  TempDir dir("serve-load");
  const fs::path pkg = dir / "surf.mbtiles";
  fs::copy_file(surface_dem() / "geodetic.mbtiles", pkg);
  const fs::path& v = vector_packages();
  ASSERT_TRUE(run_all({tiler() + " export -q " + pkg.string() + " --format quantized-mesh -o " +
                           (dir / "qm").string(),
                       vectorize() + " export -q " + (v / "roads.mbtiles").string() + " -o " +
                           (dir / "roads").string()},
                      dir.path()));
  struct Expected {
    std::string target, body;
    bool gzipped;
  };
  std::vector<Expected> tiles;
  for (const auto& e : fs::recursive_directory_iterator(dir / "qm"))
    if (e.path().extension() == ".terrain")
      tiles.push_back(
          {"/surf/" + fs::relative(e.path(), dir / "qm").string() + "?extensions=octvertexnormals",
           read_file(e.path()), false});
  for (const auto& e : fs::recursive_directory_iterator(dir / "roads"))
    if (e.path().extension() == ".pbf")
      tiles.push_back({"/roads/" + fs::relative(e.path(), dir / "roads").string(),
                       gunzip(read_file(e.path())), false});
  ASSERT_GT(tiles.size(), 20u);
  ServeProcess server({pkg.string(), (v / "roads.mbtiles").string(), "-j", "4", "--timeout", "30"},
                      dir.path());
  ASSERT_GT(server.port(), 0) << server.log();
  const int port = server.port();

  constexpr int kClients = 200, kRequests = 5;  // per client
  std::mutex mutex;
  std::vector<double> latency_ms;
  int wrong = 0;
  std::string first_wrong;
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::thread> clients;
  for (int c = 0; c < kClients; ++c)
    clients.emplace_back([&, c] {
      std::mt19937 rng{uint32_t(c)};
      for (int k = 0; k < kRequests; ++k) {
        const Expected& t = tiles[rng() % tiles.size()];
        const auto t0 = std::chrono::steady_clock::now();
        const HttpReply r = http_get(port, t.target, "", "GET", 60000);
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                .count();
        std::lock_guard lock(mutex);
        latency_ms.push_back(ms);
        if (r.status != 200 || r.body != t.body) {
          if (!wrong) first_wrong = t.target + ": " + std::to_string(r.status);
          ++wrong;
        }
      }
    });
  for (std::thread& t : clients)
    t.join();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(wrong, 0) << "first wrong answer: " << first_wrong;
  EXPECT_EQ(latency_ms.size(), size_t(kClients * kRequests));
  std::sort(latency_ms.begin(), latency_ms.end());
  std::cerr << kClients << " clients, " << latency_ms.size() << " tiles in " << seconds << " s ("
            << latency_ms.size() / seconds << " tiles/s): p50 " << latency_ms[latency_ms.size() / 2]
            << " ms, p99 " << latency_ms[latency_ms.size() * 99 / 100] << " ms\n";
  EXPECT_TRUE(server.alive());
}

// Every package's own tiles, as stored, for globe-view's remote sources:
// /NAME/{z}/{x}/{y}.globe answers the blob sqlite3 reads from the file, 404
// where there is none; the TileJSON's "globe" member has the template, each
// zoom's tile range and the metadata as the file holds it.
TEST(Serve, NativeTilesAndTheirTileJsonMemberAreTheFilesOwn) {
  TempDir dir;
  const std::string roads = (vector_packages() / "roads.mbtiles").string();
  ServeProcess serve({roads}, dir.path());
  ASSERT_GT(serve.port(), 0);
  const RunResult rows = run("sqlite3 " + roads +
                                 " 'select zoom_level, tile_column, tile_row, hex(tile_data) from "
                                 "tiles where zoom_level in (0, 5, 8) order by 1, 2, 3 limit 40'",
                             dir.path());
  ASSERT_EQ(rows.exit_code, 0) << rows.err;
  std::istringstream in(rows.out);
  int checked = 0;
  for (std::string line; std::getline(in, line);) {
    int z = 0;
    unsigned x = 0, tms_row = 0;
    char hex[8];
    ASSERT_EQ(std::sscanf(line.c_str(), "%d|%u|%u|%1s", &z, &x, &tms_row, hex), 4) << line;
    const std::string want_hex = line.substr(line.rfind('|') + 1);
    const unsigned y = (1u << z) - 1 - tms_row;
    const HttpReply r =
        http_get(serve.port(), "/roads/" + std::to_string(z) + "/" + std::to_string(x) + "/" +
                                   std::to_string(y) + ".globe");
    ASSERT_EQ(r.status, 200) << z << "/" << x << "/" << y;
    EXPECT_EQ(r.header("content-type"), "application/vnd.globe.tile");
    std::string got_hex;
    for (unsigned char c : r.body) {
      char b[3];
      std::snprintf(b, sizeof b, "%02X", c);
      got_hex += b;
    }
    EXPECT_EQ(got_hex, want_hex) << z << "/" << x << "/" << y;
    ++checked;
  }
  EXPECT_GT(checked, 3);
  EXPECT_EQ(http_get(serve.port(), "/roads/8/0/0.globe").status, 404);  // the Pacific: no tile
  // The TileJSON's member.
  const HttpReply tj = http_get(serve.port(), "/roads.json");
  ASSERT_EQ(tj.status, 200);
  const tileformat::JsonValue doc = tileformat::JsonValue::parse(tj.body);
  const tileformat::JsonValue* globe = doc.find("globe");
  ASSERT_TRUE(globe && globe->is_object()) << tj.body;
  EXPECT_EQ(globe->find("tiles")->array()[0].string(),
            "http://127.0.0.1:" + std::to_string(serve.port()) + "/roads/{z}/{x}/{y}.globe");
  const RunResult fmt = run("sqlite3 " + roads +
                                " \"select value from metadata where name = "
                                "'globe:classes'\"",
                            dir.path());
  std::string classes = fmt.out;
  while (!classes.empty() && classes.back() == '\n')
    classes.pop_back();
  EXPECT_EQ(globe->find("metadata")->find("globe:classes")->string(), classes);
  const RunResult ranges = run("sqlite3 " + roads +
                                   " 'select min(tile_column), max(tile_column) from tiles where "
                                   "zoom_level = 8'",
                               dir.path());
  bool found = false;
  for (const tileformat::JsonValue& z : globe->find("zooms")->array())
    if (z.array()[0].number() == 8) {
      found = true;
      EXPECT_EQ(std::to_string(int(z.array()[1].number())) + "|" +
                    std::to_string(int(z.array()[2].number())) + "\n",
                ranges.out);
    }
  EXPECT_TRUE(found);
}
