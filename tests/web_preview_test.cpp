// globe-serve's preview of all its packages together (issue 55 part 3), in
// the real clients (label web: headless chromium, SwiftShader WebGL): a
// terrain, two image packages (a grey relief and, over part of it, a colour
// relief), a line and a point package, served at once. MapLibre GL shows the
// terrain as raster-DEM terrain with its hillshade, the images in the order
// given, the packages' own vector styles on top; CesiumJS the quantized-mesh
// terrain, the images draped in order and the lines and points as images the
// server draws. Each view against an expected PNG.
#include <gtest/gtest.h>

#include <fstream>

#include "render_fixtures.hpp"
#include "serve_fixtures.hpp"
#include "test_paths.hpp"
#include "tileformat/json.hpp"
#include "web_fixtures.hpp"
#include "web_surfaces.hpp"

namespace {

using namespace globe_test;

// The packages, built once: surf (terrain), grey and colour (images), roads
// (lines, two classes), towns (points), all over the regional surface.
const fs::path& preview_packages() {
  static const fs::path dir = shared_folder("serve-preview", [](const fs::path& d) {
    auto at = [&](const char* name) { return (d / name).string(); };
    std::ofstream(d / "roads.geojson")
        << R"({"type":"FeatureCollection","features":[)"
        << R"({"type":"Feature","properties":{"kind":"road"},"geometry":{"type":"LineString","coordinates":[[10.3,45.4],[11.5,46.1],[12.4,46.4],[13.7,47.6]]}},)"
        << R"({"type":"Feature","properties":{"kind":"river"},"geometry":{"type":"LineString","coordinates":[[10.5,47.7],[11.2,47.0],[12.1,46.9],[13.0,46.0],[13.8,45.3]]}}]})";
    std::ofstream(d / "towns.csv") << "lon,lat,people\n11.35,46.5,107000\n12.3,45.7,90000\n"
                                      "13.1,47.3,150000\n10.9,45.45,260000\n";
    std::ofstream(d / "ramp.txt") << "500 49 54 149\n1000 116 173 209\n1500 254 224 144\n"
                                     "2000 215 48 39\n";
    const std::string tif = (surface_dem() / "surface.tif").string();
    return run_all(
        {"cp " + (surface_dem() / "mercator.mbtiles").string() + " " + at("surf.mbtiles"),
         "gdal_translate -q -ot Byte -scale " + tif + " " + at("grey.tif"),
         tiler() + " imagery -q " + at("grey.tif") + " --format png -o " + at("grey.mbtiles"),
         "gdal_translate -q -srcwin 128 96 256 192 " + tif + " " + at("part.tif"),
         "gdaldem color-relief -q -alpha " + at("part.tif") + " " + at("ramp.txt") + " " +
             at("colour.tif"),
         tiler() + " imagery -q " + at("colour.tif") + " --format png -o " + at("colour.mbtiles"),
         vectorize() + " lines -q " + at("roads.geojson") +
             " --class-field kind --max-zoom 10 --style 'road:color=#d7301f,width=4px' --style "
             "'river:color=#2171b5,width=3px' -o " +
             at("roads.mbtiles"),
         vectorize() + " points -q " + at("towns.csv") +
             " --xy lon,lat --fields people --max-zoom 10 -o " + at("towns.mbtiles")},
        d);
  });
  return dir;
}

// globe-serve with the packages in this order and the browser libraries.
struct PreviewServer {
  explicit PreviewServer(const TempDir& dir) {
    const fs::path& d = preview_packages();
    const RunResult cache =
        run(globe_test::paths::test_data_dir() + "/../../scripts/web-deps.sh", dir.path());
    EXPECT_EQ(cache.exit_code, 0) << cache.err;
    const std::string libs =
        cache.out.substr(0, cache.out.find_last_not_of('\n') + 1) + "/node_modules";
    server = std::make_unique<ServeProcess>(
        std::vector<std::string>{(d / "surf.mbtiles").string(), (d / "grey.mbtiles").string(),
                                 (d / "colour.mbtiles").string(), (d / "roads.mbtiles").string(),
                                 (d / "towns.mbtiles").string(), "--web-libs", libs},
        dir.path());
    url = "http://127.0.0.1:" + std::to_string(server->port());
  }
  std::unique_ptr<ServeProcess> server;
  std::string url;
};

std::string names(const tileformat::JsonValue& array) {
  std::string out;
  for (const auto& v : array.array())
    out += (out.empty() ? "" : ",") + v.string();
  return out;
}

TEST(WebServePreview, MapLibreShowsEveryPackageTogether) {
  TempDir dir("web-preview-maplibre");
  PreviewServer s(dir);
  ASSERT_GT(s.server->port(), 0) << s.server->log();
  const fs::path shot = dir / "maplibre.png";
  const RunResult page =
      run_web_page(s.url + "/view/maplibre.html", dir.path(), "", shot, dir.path(), "480x360");
  ASSERT_EQ(page.exit_code, 0) << page.err << s.server->log();
  const auto result = tileformat::JsonValue::parse(page.out);
  EXPECT_EQ(result.find("terrain")->string(), "surf");
  EXPECT_EQ(result.find("skipped")->array().size(), 0u) << page.out;
  // Bottom to top: the images in the order given, the hillshade, the lines'
  // casings and fills and the points of their own styles.
  EXPECT_EQ(names(*result.find("layers")),
            "background,grey,colour,hillshade,roads/roads/road,roads/roads/river,towns/points")
      << page.out;
  for (const char* asked :
       {"GET /surf/", "GET /grey/", "GET /colour/", "GET /roads/", "GET /towns/"})
    EXPECT_NE(s.server->log().find(asked), std::string::npos) << asked;
  expect_image(shot.string(), "serve_preview_maplibre");
}

TEST(WebServePreview, CesiumShowsEveryPackageTogether) {
  TempDir dir("web-preview-cesium");
  PreviewServer s(dir);
  ASSERT_GT(s.server->port(), 0) << s.server->log();
  const fs::path shot = dir / "cesium.png";
  const RunResult page =
      run_web_page(s.url + "/view/cesium.html", dir.path(), "", shot, dir.path(), "480x360");
  ASSERT_EQ(page.exit_code, 0) << page.err << s.server->log();
  const auto result = tileformat::JsonValue::parse(page.out);
  EXPECT_EQ(result.find("terrain")->string(), "surf");
  EXPECT_EQ(names(*result.find("draped")), "grey,colour,roads,towns") << page.out;
  for (const char* asked :
       {"GET /surf/", "GET /grey/", "GET /colour/", "GET /roads/", "GET /towns/"})
    EXPECT_NE(s.server->log().find(asked), std::string::npos) << asked;
  expect_image(shot.string(), "serve_preview_cesium");
}

}  // namespace
