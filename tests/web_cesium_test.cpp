// Quantized-mesh exports in CesiumJS (label web): headless Debian chromium
// (SwiftShader WebGL) driven by playwright-core, the folder served from
// 127.0.0.1 (tests/web/README.md). The expected heights come from the
// exported tiles decoded here (spec_readers/) and from the analytic source.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "quantized_mesh_fixtures.hpp"
#include "render_fixtures.hpp"
#include "serve_fixtures.hpp"
#include "test_paths.hpp"
#include "tileformat/json.hpp"
#include "web_fixtures.hpp"
#include "web_surfaces.hpp"

namespace {

using namespace globe_test;

}  // namespace

// CesiumJS as a user's page: CesiumTerrainProvider over the exported folder
// (layer.json, vertex normals), sampleTerrainMostDetailed at 30 points equal
// to the exported mesh there (the source's heights at the enclosing
// triangle's vertices, interpolated in the triangle) within the height step,
// the quantization and 0.1 m, p90 within 10 m of the plain source.
TEST(WebCesium, SampledHeightsAreTheExportedMesh) {
  const fs::path& d = surface_dem();
  TempDir dir("web-cesium");
  const fs::path out = dir.path() / "terrain";
  const RunResult r = run(tiler() + " export -q " + (d / "geodetic.mbtiles").string() +
                              " --format quantized-mesh -o " + out.string(),
                          dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const MeshTiles tiles = read_mesh_folder(out, false);
  const double step = std::stod(run("sqlite3 " + (d / "geodetic.mbtiles").string() +
                                        " \"SELECT value FROM metadata WHERE name = "
                                        "'globe:height_step'\"",
                                    dir.path())
                                    .out);

  std::vector<std::pair<double, double>> points;
  std::ostringstream query;
  query.precision(10);
  query << "terrain=/data/terrain&points=";
  for (int k = 0; k < 30; ++k) {  // a low-discrepancy spread over the surface's inside
    const double lon =
        kRegional.west + 0.1 +
        (kRegional.east - kRegional.west - 0.2) * std::fmod(0.5 + k * 0.618033988749895, 1.0);
    const double lat =
        kRegional.south + 0.1 +
        (kRegional.north - kRegional.south - 0.2) * std::fmod(0.5 + k * 0.754877666246693, 1.0);
    points.push_back({lon, lat});
    query << (k ? ";" : "") << lon << "," << lat;
  }
  const fs::path shot = dir.path() / "cesium.png";
  const RunResult page =
      run_web_page("cesium_terrain.html", dir.path(), query.str(), shot, dir.path(), "480x320");
  ASSERT_EQ(page.exit_code, 0) << page.err;
  const tileformat::JsonValue result = tileformat::JsonValue::parse(page.out);
  EXPECT_TRUE(result.find("hasVertexNormals")->boolean());
  const auto& heights = result.find("heights")->array();
  ASSERT_EQ(heights.size(), points.size());

  std::vector<double> plain;
  for (size_t k = 0; k < points.size(); ++k) {
    const auto [lon, lat] = points[k];
    const MeshTile* t = finest_tile_at(tiles, lon, lat);
    ASSERT_TRUE(t) << lon << ", " << lat;
    // The source at each vertex's decoded position, interpolated in the triangle.
    const std::optional<double> mesh = mesh_height_at(*t, lon, lat, [&](size_t v) {
      return kRegional.bilinear(t->vertex_lon(v), t->vertex_lat(v));
    });
    ASSERT_TRUE(mesh);
    const double got = heights[k].number();
    const double position = kRegional.amp *
                            (kRegional.kx * (t->rect.east - t->rect.west) +
                             kRegional.ky * (t->rect.north - t->rect.south)) /
                            (2 * qm::kQuantizedMax);
    EXPECT_NEAR(got, *mesh, step / 2 + t->quantum() / 2 + position + 0.1)
        << "point " << k << " (" << lon << ", " << lat << ") in tile " << t->z << "/" << t->x << "/"
        << t->y;
    plain.push_back(std::fabs(got - kRegional.bilinear(lon, lat)));
  }
  std::sort(plain.begin(), plain.end());
  const double p90 = plain[plain.size() * 9 / 10];
  EXPECT_LE(p90, 10.0) << "p90 against the plain source";
  std::cerr << "cesium " << result.find("cesium")->string() << ": p90 " << p90
            << " m from the plain source, max " << plain.back() << " m\n";
}

// The jacksboro DEM as a geodetic package and its quantized-mesh export, once
// per test binary.
const fs::path& jacksboro_mesh() {
  static const fs::path dir = shared_folder("cesium-jacksboro", [](const fs::path& d) {
    const std::string pkg = (d / "j.mbtiles").string();
    return run_all(
        {tiler() + " terrain -q --tiling geodetic " + sample("jacksboro.tif").string() + " -o " +
             pkg,
         tiler() + " export -q " + pkg + " --format quantized-mesh -o " + (d / "terrain").string()},
        d);
  });
  return dir;
}

// The jacksboro DEM as a user's page shows it from `terrain` (a path under
// the page's server or a URL): lit by the tiles' vertex normals, oblique,
// against its expected image.
void expect_jacksboro_lit(const std::string& terrain, const TempDir& dir) {
  const fs::path shot = dir.path() / "cesium.png";
  const RunResult page = run_web_page(
      "cesium_terrain.html", jacksboro_mesh(),
      "terrain=" + terrain + "&exaggeration=1.5&camera=-84.25,36.45,6000,0,-30&points=-84.2,36.55",
      shot, dir.path(), "480x320");
  ASSERT_EQ(page.exit_code, 0) << page.err;
  const tileformat::JsonValue result = tileformat::JsonValue::parse(page.out);
  EXPECT_TRUE(result.find("hasVertexNormals")->boolean());
  EXPECT_TRUE(result.find("rendered")->find("tilesLoaded")->boolean());
  expect_image(shot.string(), "cesium_jacksboro_lit");
}

// The static export.
TEST(WebCesium, RealReliefLitByTheVertexNormals) {
  TempDir dir("web-cesium-view");
  expect_jacksboro_lit("/data/terrain", dir);
}

// globe-serve cutting the same tiles on the fly: the same picture.
TEST(WebCesium, GlobeServeRealReliefLitByTheVertexNormals) {
  TempDir dir("web-cesium-serve-view");
  ServeProcess server({(jacksboro_mesh() / "j.mbtiles").string()}, dir.path());
  ASSERT_GT(server.port(), 0) << server.log();
  expect_jacksboro_lit("http://127.0.0.1:" + std::to_string(server.port()) + "/j/", dir);
  EXPECT_NE(server.log().find("GET /j/"), std::string::npos) << "Cesium asked for no tile";
}

// globe-serve in the real clients: CesiumJS samples the same heights from the
// tiles the server cuts on the fly as from the static export (the same
// tiles), and the server's own MapLibre preview of the terrain (raster-DEM
// cut on the fly, the library served from its /lib) loads without an error.
TEST(WebCesium, GlobeServeTerrainInCesiumAndItsMapLibrePreview) {
  const fs::path& d = surface_dem();
  TempDir dir("web-serve");
  fs::copy_file(d / "geodetic.mbtiles", dir / "surf.mbtiles");
  ASSERT_TRUE(run_all({tiler() + " export -q " + (dir / "surf.mbtiles").string() +
                       " --format quantized-mesh -o " + (dir / "terrain").string()},
                      dir.path()));
  // The web cache, as run_web_page installs it, is what the server serves at /lib.
  const RunResult cache =
      run(globe_test::paths::test_data_dir() + "/../../scripts/web-deps.sh", dir.path());
  ASSERT_EQ(cache.exit_code, 0) << cache.err;
  const std::string libs =
      cache.out.substr(0, cache.out.find_last_not_of('\n') + 1) + "/node_modules";
  ServeProcess server({(dir / "surf.mbtiles").string(), "--web-libs", libs}, dir.path());
  ASSERT_GT(server.port(), 0) << server.log();
  const std::string url = "http://127.0.0.1:" + std::to_string(server.port());
  const std::string points = "points=11.3,46.2;12.7,47.1;13.5,45.6;10.9,47.7;12.02,46.55";
  const RunResult served =
      run_web_page("cesium_terrain.html", dir.path(), "terrain=" + url + "/surf/&" + points,
                   dir / "served.png", dir.path());
  ASSERT_EQ(served.exit_code, 0) << served.err << server.log();
  const RunResult exported =
      run_web_page("cesium_terrain.html", dir.path(), "terrain=/data/terrain&" + points,
                   dir / "exported.png", dir.path());
  ASSERT_EQ(exported.exit_code, 0) << exported.err;
  const auto a = tileformat::JsonValue::parse(served.out).find("heights")->array();
  const auto b = tileformat::JsonValue::parse(exported.out).find("heights")->array();
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k)
    EXPECT_NEAR(a[k].number(), b[k].number(), 1e-6) << "point " << k;
  EXPECT_TRUE(tileformat::JsonValue::parse(served.out).find("hasVertexNormals")->boolean());

  const RunResult preview = run_web_page(url + "/view/maplibre.html", dir.path(),
                                         "pkg=surf&kind=terrain", dir / "preview.png", dir.path());
  ASSERT_EQ(preview.exit_code, 0) << preview.err << server.log();
  EXPECT_TRUE(tileformat::JsonValue::parse(preview.out).find("loaded")->boolean());
  EXPECT_NE(server.log().find("GET /surf/"), std::string::npos) << "MapLibre asked for no tile";
}
