// Exports in a real client (label web): MapLibre GL JS in headless Debian
// chromium (SwiftShader WebGL) driven by playwright-core, the page served
// from 127.0.0.1 with HTTP ranges (tests/web/README.md). The expected values
// come from the exported tiles decoded here (spec_readers/, GDAL's PNG
// driver) and from the plain source DEM.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include <ogr_api.h>
#include <ogr_srs_api.h>

#include "area_fixtures.hpp"
#include "render_fixtures.hpp"
#include "serve_fixtures.hpp"
#include "spec_readers/pmtiles_reader.hpp"
#include "spec_readers/raster_dem.hpp"
#include "tileformat/json.hpp"
#include "web_fixtures.hpp"

namespace {

using namespace globe_test;
namespace pmr = spec_readers::pmtiles;
namespace dem = spec_readers::raster_dem;
constexpr double kPi = 3.14159265358979323846;

}  // namespace

// The jacksboro DEM as a package and its Terrarium PMTiles export, once per
// test binary.
const fs::path& jacksboro_terrarium() {
  static const fs::path dir = shared_folder("maplibre-jacksboro", [](const fs::path& d) {
    const std::string pkg = (d / "jb.mbtiles").string();
    return run_all(
        {tiler() + " terrain -q " + sample("jacksboro.tif").string() + " -o " + pkg,
         tiler() + " export -q " + pkg + " --format terrarium -o " + (d / "jb.pmtiles").string()},
        d);
  });
  return dir;
}

// MapLibre GL JS, as a user's page, with the jacksboro DEM's Terrarium tiles
// from `tiles_query` (the page's query: a PMTiles path or a TileJSON URL), 3D
// terrain: queryTerrainElevation at 30 points equals the bilinear
// interpolation of the pixel centres of the exported tiles (decoded here) of
// the tile MapLibre drew there, the finest for most (a parent, or the tile's
// own edge pixels across a border whose neighbour has not loaded, are
// MapLibre's own fallbacks), and p90 is within 10 m of the plain source DEM.
void expect_terrarium_elevations(const std::string& tiles_query, const TempDir& dir) {
  const std::string file = read_file(jacksboro_terrarium() / "jb.pmtiles");
  const int zmax = pmr::read_header(file).max_zoom;
  const double lon0 = -84.2458, lat0 = 36.5896;
  // The finest tiles' pixels, decoded on demand.
  std::map<std::tuple<int, uint32_t, uint32_t>, std::vector<uint8_t>> tiles;
  auto pixel = [&](int zoom, int64_t gx, int64_t gy) {
    const auto key = std::tuple(zoom, uint32_t(gx / 256), uint32_t(gy / 256));
    auto it = tiles.find(key);
    if (it == tiles.end()) {
      const auto bytes = pmr::get_tile(file, zoom, std::get<1>(key), std::get<2>(key));
      int w = 0, h = 0;
      it = tiles.emplace(key, bytes ? png_rgb(*bytes, w, h) : std::vector<uint8_t>{}).first;
    }
    if (it->second.empty()) return std::nan("");
    return dem::pixel_height(it->second.data(), 256, 256, 3, int(gx % 256), int(gy % 256),
                             dem::Encoding::Terrarium);
  };
  // clamped: the tile's own edge pixels stand in for its neighbours' (what
  // MapLibre interpolates at a tile's border until the neighbour has loaded).
  auto expected = [&](double lon, double lat, int zoom, bool clamped = false) {
    const double n = std::ldexp(256.0, zoom);
    const double gx = (lon + 180) / 360 * n,
                 gy = (1 - std::asinh(std::tan(lat * kPi / 180)) / kPi) / 2 * n;
    const double u = gx - 0.5, v = gy - 0.5;
    const int64_t i = int64_t(std::floor(u)), j = int64_t(std::floor(v));
    const double a = u - i, b = v - j;
    const int64_t tx = int64_t(gx) / 256 * 256, ty = int64_t(gy) / 256 * 256;
    auto at = [&](int64_t x, int64_t y) {
      if (clamped) x = std::clamp(x, tx, tx + 255), y = std::clamp(y, ty, ty + 255);
      return pixel(zoom, x, y);
    };
    return (1 - b) * ((1 - a) * at(i, j) + a * at(i + 1, j)) +
           b * ((1 - a) * at(i, j + 1) + a * at(i + 1, j + 1));
  };
  // The plain source: NAD83 degrees at 3", pixels as areas.
  gdal_setup();
  GDALDatasetH src = GDALOpen(sample("jacksboro.tif").c_str(), GA_ReadOnly);
  ASSERT_NE(src, nullptr);
  double sgt[6];
  GDALGetGeoTransform(src, sgt);
  const int sw = GDALGetRasterXSize(src), sh = GDALGetRasterYSize(src);
  std::vector<float> heights(size_t(sw) * sh);
  ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(src, 1), GF_Read, 0, 0, sw, sh, heights.data(), sw, sh,
                         GDT_Float32, 0, 0),
            CE_None);
  GDALClose(src);
  auto source = [&](double lon, double lat) {
    const double u = (lon - sgt[0]) / sgt[1] - 0.5, v = (lat - sgt[3]) / sgt[5] - 0.5;
    const int i = int(std::floor(u)), j = int(std::floor(v));
    const double a = u - i, b = v - j;
    auto at = [&](int x, int y) { return double(heights[size_t(y) * sw + x]); };
    return (1 - b) * ((1 - a) * at(i, j) + a * at(i + 1, j)) +
           b * ((1 - a) * at(i, j + 1) + a * at(i + 1, j + 1));
  };
  std::string points;
  std::vector<std::pair<double, double>> where;
  for (int k = 0; k < 30; ++k) {
    const double lon = lon0 - 0.05 + 0.1 * ((k * 7) % 30) / 29.0;
    const double lat = lat0 - 0.03 + 0.06 * ((k * 11) % 30) / 29.0;
    where.emplace_back(lon, lat);
    char p[64];
    std::snprintf(p, sizeof p, "%s%.6f,%.6f", k ? ";" : "", lon, lat);
    points += p;
  }
  const RunResult page = run_web_page(
      "maplibre_dem.html", jacksboro_terrarium(),
      tiles_query + "&encoding=terrarium&center=" + std::to_string(lon0) + "," +
          std::to_string(lat0) + "&zoom=" + std::to_string(zmax + 1) + "&points=" + points,
      dir / "maplibre.png", dir.path());
  ASSERT_EQ(page.exit_code, 0) << page.err;
  const auto result = tileformat::JsonValue::parse(page.out);
  const auto& got = result.find("elevations")->array();
  ASSERT_EQ(got.size(), where.size());
  std::vector<double> off_source;
  double worst = 0;
  int finest = 0;
  for (size_t k = 0; k < where.size(); ++k) {
    ASSERT_TRUE(got[k].is_number()) << "no elevation at point " << k;
    // MapLibre interpolates the DEM tile it drew there: the finest, or a
    // parent where the finest is not loaded (at the view's edge), with its
    // neighbours' pixels across its border, or its own before they load.
    double off = 1e300;
    int zoom = zmax;
    for (int z = zmax; z >= std::max(0, zmax - 3) && off > 0.02; --z)
      for (bool clamped : {false, true}) {
        const double d =
            std::fabs(got[k].number() - expected(where[k].first, where[k].second, z, clamped));
        if (d < off) off = d, zoom = z;
      }
    finest += zoom == zmax;
    worst = std::max(worst, off);
    EXPECT_LE(off, 0.02) << "point " << k << " (" << where[k].first << ", " << where[k].second
                         << "): " << got[k].number() << " m, the finest tiles' pixels give "
                         << expected(where[k].first, where[k].second, zmax) << " m";
    off_source.push_back(std::fabs(got[k].number() - source(where[k].first, where[k].second)));
  }
  EXPECT_GE(finest, 25) << "points where MapLibre drew the finest tiles";
  std::sort(off_source.begin(), off_source.end());
  const double p90 = off_source[off_source.size() * 9 / 10];
  EXPECT_LE(p90, 10.0);
  std::printf(
      "MapLibre %s: 30 points (%d on the finest tiles), worst %.4f m from the tiles' "
      "pixels; p90 %.2f m, max %.2f m from the plain source\n",
      result.find("maplibre")->string().c_str(), finest, worst, p90, off_source.back());
}

// URL-encoded for a query parameter.
std::string query_escape(const std::string& s) {
  std::string out;
  for (const unsigned char c : s) {
    if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~' || c == '/' || c == ':') {
      out += char(c);
    } else {
      char hex[4];
      std::snprintf(hex, sizeof hex, "%%%02X", c);
      out += hex;
    }
  }
  return out;
}

// The exported PMTiles file, served over HTTP with ranges.
TEST(WebMapLibre, TerrariumPmtilesElevationsAreTheTilesPixels) {
  TempDir dir;
  expect_terrarium_elevations("pmtiles=/data/jb.pmtiles", dir);
}

// globe-serve cutting the same tiles on the fly from the package, found
// through its raster-DEM TileJSON: the same elevations.
TEST(WebMapLibre, GlobeServeTerrariumElevationsAreTheTilesPixels) {
  TempDir dir;
  ServeProcess server({(jacksboro_terrarium() / "jb.mbtiles").string()}, dir.path());
  ASSERT_GT(server.port(), 0) << server.log();
  expect_terrarium_elevations(
      "tilejson=" + query_escape("http://127.0.0.1:" + std::to_string(server.port()) +
                                 "/jb.json?encoding=terrarium"),
      dir);
  EXPECT_NE(server.log().find("GET /jb/"), std::string::npos) << "MapLibre asked for no tile";
}

// The US flights bundled over the airways as a package, its MVT PMTiles
// export and the generated style, once per test binary.
const fs::path& flights_mvt() {
  static const fs::path dir = shared_folder("maplibre-flights", [](const fs::path& d) {
    const std::string pkg = (d / "flights.mbtiles").string();
    return run_all({vectorize() + " bundle -q " + sample("us_flights_airport.csv").string() +
                        " --from-id origin --to-id destination --weight count --locations " +
                        sample("us_airports.csv").string() + " --id-field iata --network " +
                        sample("airways.geojson").string() + " -o " + pkg,
                    vectorize() + " export -q " + pkg + " -o " + (d / "flights.pmtiles").string() +
                        " --style-json " + (d / "style.json").string()},
                   d);
  });
  return dir;
}

// MapLibre draws the flights from `source` (the page's query: the style and
// where its tiles are) with the generated style: the weight classes the view
// holds with the style's layers, every feature it renders a bundle or
// unrouted line of the package's features table (read with the sqlite3
// program), the picture the expected one.
void expect_flights_drawn(const std::string& source, const TempDir& dir) {
  const fs::path pkg = flights_mvt() / "flights.mbtiles";
  const RunResult page =
      run_web_page("maplibre_mvt.html", flights_mvt(), source + "&center=-97,39&zoom=3.5",
                   dir / "mvt.png", dir.path(), "480x320");
  ASSERT_EQ(page.exit_code, 0) << page.err;
  const auto result = tileformat::JsonValue::parse(page.out);
  const RunResult rows = run("sqlite3 " + pkg.string() +
                                 " \"SELECT id FROM features WHERE layer IN ('bundles', "
                                 "'unrouted')\"",
                             dir.path());
  std::set<int64_t> drawable;
  std::istringstream in(rows.out);
  for (int64_t id; in >> id;)
    drawable.insert(id);
  const auto& ids = result.find("ids")->array();
  EXPECT_GT(ids.size(), 100u) << "bundles rendered at the continental view";
  for (const auto& id : ids)
    EXPECT_TRUE(drawable.count(int64_t(id.number()))) << "rendered id " << id.number();
  const auto& layers = result.find("layers")->members();
  std::set<std::string> drawn;
  for (const auto& [name, count] : layers)
    if (count.number() > 0) drawn.insert(name);
  for (const char* heavy : {"bundles/weight-1", "bundles/weight-6"})
    EXPECT_TRUE(drawn.count(heavy)) << heavy << " not drawn; drawn: " << page.out.substr(0, 300);
  std::printf("MapLibre drew %zu features of %zu style layers\n", ids.size(), drawn.size());
  expect_image((dir / "mvt.png").string(), "maplibre_us_flights_mvt");
}

// The MVT PMTiles export with the style export --style-json wrote.
TEST(WebMapLibre, BundlesAsMvtPmtilesDrawWithTheGeneratedStyle) {
  TempDir dir;
  expect_flights_drawn("style=/data/style.json&pmtiles=/data/flights.pmtiles", dir);
}

// globe-serve encoding the same tiles per request, with its own style (its
// source the server's TileJSON): the same picture.
TEST(WebMapLibre, GlobeServeBundlesDrawWithItsStyle) {
  TempDir dir;
  ServeProcess server({(flights_mvt() / "flights.mbtiles").string()}, dir.path());
  ASSERT_GT(server.port(), 0) << server.log();
  expect_flights_drawn("style=" + query_escape("http://127.0.0.1:" + std::to_string(server.port()) +
                                               "/flights/style.json"),
                       dir);
  EXPECT_NE(server.log().find("GET /flights/"), std::string::npos) << "MapLibre asked for no tile";
}

// The same archive read by pmtiles.js from globe-serve (issue 55): its first
// read asks bytes=0-16383, then directories and tiles by ranges, every one
// answered as RFC 9110 says (the picture is the same).
TEST(WebMapLibre, PmtilesFromGlobeServeByRanges) {
  TempDir dir;
  ServeProcess server({(flights_mvt() / "flights.pmtiles").string()}, dir.path());
  ASSERT_GT(server.port(), 0) << server.log();
  expect_flights_drawn(
      "style=/data/style.json&pmtiles=" +
          query_escape("http://127.0.0.1:" + std::to_string(server.port()) + "/flights.pmtiles"),
      dir);
  EXPECT_NE(server.log().find("GET /flights.pmtiles 206"), std::string::npos) << server.log();
}

// nc.gpkg's counties as a choropleth of BIR74 in 4 quantile classes,
// served by globe-serve and drawn by MapLibre with the server's own style
// (its fills at 0.8 over the page's #f4f1ea): every county rendered, the
// picture the expected one, and, independently of it, at the inside point
// of every county at least 6 px from its border, the pixel the colour of the
// county's class (computed here from BIR74 and the breaks `info --json`
// lists) blended at 0.8, nearer it than any other class's.
TEST(WebMapLibre, AreasChoroplethFromGlobeServe) {
  TempDir dir;
  const std::string pkg = (dir / "nc.mbtiles").string();
  ASSERT_TRUE(run_all({vectorize() + " areas -q " + sample("nc.gpkg").string() +
                       " --choropleth BIR74 --classes 4 --max-zoom 7 -o " + pkg},
                      dir.path()));
  const RunResult info = run(vectorize() + " info --json " + pkg, dir.path());
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const auto json = tileformat::JsonValue::parse(info.out);
  struct Class {
    double min;
    std::array<int, 3> rgb;
  };
  std::vector<Class> classes;
  double top = 0;
  for (const auto& c : json.find("areas")->find("classes")->array()) {
    unsigned r = 0, g = 0, b = 0;
    std::sscanf(c.find("color")->string().c_str(), "#%2x%2x%2x", &r, &g, &b);
    classes.push_back({c.find("min")->number(), {int(r), int(g), int(b)}});
    top = c.find("max")->number();
  }
  ASSERT_EQ(classes.size(), 4u);
  ServeProcess server({pkg}, dir.path());
  ASSERT_GT(server.port(), 0) << server.log();
  // The view: 640 x 280 px around the state at zoom 5.5 (MapLibre's 512 px
  // world at zoom 0).
  const int width = 640, height = 280;
  const double lon0 = -79.89, lat0 = 35.24, zoom = 5.5;
  const RunResult page = run_web_page(
      "maplibre_mvt.html", dir.path(),
      "style=" +
          query_escape("http://127.0.0.1:" + std::to_string(server.port()) + "/nc/style.json") +
          "&center=" + std::to_string(lon0) + "," + std::to_string(lat0) +
          "&zoom=" + std::to_string(zoom),
      dir / "areas.png", dir.path(), std::to_string(width) + "x" + std::to_string(height));
  ASSERT_EQ(page.exit_code, 0) << page.err;
  const auto result = tileformat::JsonValue::parse(page.out);
  std::set<int64_t> ids;
  for (const auto& id : result.find("ids")->array())
    ids.insert(int64_t(id.number()));
  EXPECT_EQ(ids.size(), 100u) << "every county rendered: " << page.out.substr(0, 300);
  const auto* fills = result.find("layers")->find("nc.gpkg/choropleth");
  ASSERT_TRUE(fills) << page.out.substr(0, 300);
  EXPECT_GE(fills->number(), 100);
  EXPECT_NE(server.log().find("GET /nc/"), std::string::npos) << "MapLibre asked for no tile";
  expect_image((dir / "areas.png").string(), "maplibre_areas_choropleth");

  int w = 0, h = 0;
  const std::vector<uint8_t> rgb = read_rgb((dir / "areas.png").string(), w, h);
  ASSERT_EQ(w, width);
  ASSERT_EQ(h, height);
  const std::array<int, 3> bg{0xf4, 0xf1, 0xea};
  auto blend = [&](const std::array<int, 3>& c) {
    std::array<double, 3> out{};
    for (int b = 0; b < 3; ++b)
      out[size_t(b)] = 0.8 * c[size_t(b)] + 0.2 * bg[size_t(b)];
    return out;
  };
  const double world = 512 * std::pow(2.0, zoom);
  auto mercator_y = [](double lat) {
    return (1 - std::asinh(std::tan(lat * kPi / 180)) / kPi) / 2;
  };
  std::map<int, int> checked;  // per class
  for (const County& c : nc_counties()) {
    if (c.clearance * world / 360 < 6) continue;
    int k = 0;
    for (size_t i = 0; i < classes.size(); ++i)
      if (c.births >= classes[i].min) k = int(i);
    ASSERT_LE(c.births, top) << c.name;
    const int x = int(std::floor(width / 2.0 + (c.lon - lon0) / 360 * world));
    const int y = int(std::floor(height / 2.0 + (mercator_y(c.lat) - mercator_y(lat0)) * world));
    ASSERT_TRUE(x >= 0 && y >= 0 && x < w && y < h) << c.name;
    const uint8_t* p = &rgb[(size_t(y) * w + x) * 3];
    const auto want = blend(classes[size_t(k)].rgb);
    // The nearest class colour is the county's, and it is that colour.
    int nearest = -1;
    double best = 1e9;
    for (size_t i = 0; i < classes.size(); ++i) {
      const auto b = blend(classes[i].rgb);
      double d = 0;
      for (int j = 0; j < 3; ++j)
        d += std::abs(p[j] - b[size_t(j)]);
      if (d < best) best = d, nearest = int(i);
    }
    EXPECT_EQ(nearest, k) << c.name << " (BIR74 " << c.births << ") at " << x << "," << y;
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(p[j], want[size_t(j)], 3) << c.name << " (BIR74 " << c.births << ", class "
                                            << k + 1 << ") at " << x << "," << y << " band " << j;
    ++checked[k];
  }
  for (int k = 0; k < 4; ++k)
    EXPECT_GE(checked[k], 3) << "counties checked in class " << k + 1;
  std::printf(
      "MapLibre drew %zu counties; %d, %d, %d, %d checked per class at their inside point\n",
      ids.size(), checked[0], checked[1], checked[2], checked[3]);
}

// The world's countries (world.gpkg) labelled by name_long as an area
// package, its MVT PMTiles export, the style and, beside it, the glyphs
// (fonts/), once per test binary.
const fs::path& world_labels() {
  static const fs::path dir = shared_folder("maplibre-world-labels", [](const fs::path& d) {
    const std::string pkg = (d / "world.mbtiles").string();
    return run_all({vectorize() + " areas -q " + sample("world.gpkg").string() +
                        " --label-field name_long --max-zoom 4 -o " + pkg,
                    vectorize() + " export -q " + pkg + " -o " + (d / "world.pmtiles").string() +
                        " --style-json " + (d / "style.json").string()},
                   d);
  });
  return dir;
}

// MapLibre writes the countries' names from `source` (the page's query: the
// style and where its tiles are) with the glyphs the style names, 512 x 256
// px over Europe at zoom 2.5: the symbol layer's names are labels of the
// package (read with the sqlite3 program) whose anchors lie in the view (or
// within 80 px of it: a name's box may reach in), the large countries
// there among them, and the picture is the expected one.
void expect_world_labels_drawn(const std::string& source, const TempDir& dir) {
  const fs::path pkg = world_labels() / "world.mbtiles";
  const int width = 512, height = 256;
  const double lon0 = 15, lat0 = 50, zoom = 2.5;
  const RunResult page = run_web_page("maplibre_mvt.html", world_labels(),
                                      source + "&center=" + std::to_string(lon0) + "," +
                                          std::to_string(lat0) + "&zoom=" + std::to_string(zoom),
                                      dir / "labels.png", dir.path(),
                                      std::to_string(width) + "x" + std::to_string(height));
  ASSERT_EQ(page.exit_code, 0) << page.err;
  const auto result = tileformat::JsonValue::parse(page.out);
  const RunResult rows =
      run("sqlite3 -separator '|' " + pkg.string() + " \"SELECT lon, lat, text FROM labels\"",
          dir.path());
  ASSERT_EQ(rows.exit_code, 0) << rows.err;
  const double world = 512 * std::pow(2.0, zoom);
  auto mercator_y = [](double lat) {
    return (1 - std::asinh(std::tan(lat * kPi / 180)) / kPi) / 2;
  };
  std::map<std::string, std::pair<double, double>> anchors;  // name -> view pixel
  std::istringstream in(rows.out);
  for (std::string line; std::getline(in, line);) {
    const size_t a = line.find('|'), b = line.find('|', a + 1);
    const double lon = std::stod(line.substr(0, a)), lat = std::stod(line.substr(a + 1, b - a - 1));
    anchors[line.substr(b + 1)] = {width / 2.0 + (lon - lon0) / 360 * world,
                                   height / 2.0 + (mercator_y(lat) - mercator_y(lat0)) * world};
  }
  ASSERT_EQ(anchors.size(), 177u);
  const auto* names = result.find("names") ? result.find("names")->find("labels") : nullptr;
  ASSERT_TRUE(names) << "no names drawn: " << page.out.substr(0, 400);
  std::set<std::string> drawn;
  for (const auto& n : names->array()) {
    ASSERT_TRUE(anchors.count(n.string())) << n.string() << " is no label of the package";
    const auto [x, y] = anchors.at(n.string());
    EXPECT_TRUE(x > -80 && x < width + 80 && y > -80 && y < height + 80)
        << n.string() << " drawn with its anchor at " << x << "," << y;
    drawn.insert(n.string());
  }
  EXPECT_EQ(drawn.size(), names->array().size()) << "a name written twice";
  for (const char* name :
       {"France", "Germany", "Poland", "Italy", "Ukraine", "Romania", "United Kingdom", "Belarus"})
    EXPECT_TRUE(drawn.count(name)) << name << " not written; written: " << page.out.substr(0, 600);
  EXPECT_GE(drawn.size(), 15u);
  std::printf("MapLibre wrote %zu country names\n", drawn.size());
  expect_image((dir / "labels.png").string(), "maplibre_world_labels");
}

// The export's style, its relative glyphs (fonts/ beside it) and PMTiles.
TEST(WebMapLibre, ExportedLabelsDrawWithTheirOwnGlyphs) {
  TempDir dir;
  expect_world_labels_drawn("style=/data/style.json&pmtiles=/data/world.pmtiles", dir);
}

// globe-serve's style, tiles and glyphs (/fonts, made on first ask): the
// same names and picture.
TEST(WebMapLibre, GlobeServeLabelsDrawWithItsGlyphs) {
  TempDir dir;
  ServeProcess server({(world_labels() / "world.mbtiles").string()}, dir.path());
  ASSERT_GT(server.port(), 0) << server.log();
  expect_world_labels_drawn(
      "style=" +
          query_escape("http://127.0.0.1:" + std::to_string(server.port()) + "/world/style.json"),
      dir);
  EXPECT_NE(server.log().find("GET /fonts/"), std::string::npos) << "MapLibre asked for no glyphs";
  EXPECT_NE(server.log().find("0-255.pbf 200"), std::string::npos) << server.log();
}
