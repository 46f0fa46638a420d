// Layers that compose freely (docs/viewer.md "Layers in another tiling",
// "Without terrain"):
//  - lines and points in another tiling than the terrain's: webmercator
//    contours and places over a geodetic globe, and geodetic ones over a
//    webmercator globe, drawn at the same camera as the same data in the
//    terrain's own tiling. The reference picture shares no crossing code (its
//    layer is in the terrain's tiling); at least 97 % of each picture's line
//    or chart pixels lie within 1.5 px of the other's, at mid latitudes, near
//    the pole of webmercator's reach and across the antimeridian;
//  - lines and points without terrain, against the same layer over a
//    terrain of zero heights made by gdal_create and the tiler.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "render_fixtures.hpp"
#include "test_support.hpp"

namespace {

using namespace globe_test;

struct Packages {
  fs::path dir;
  std::string at(const std::string& name) const { return (dir / name).string(); }
};

// etopo20 as a geodetic and a webmercator terrain; its 1000 m contours and a
// 20-degree grid of places, each in both tilings. Places never merge
// (--merge-px 0), so both tilings hold the same charts at every zoom.
const Packages& packages() {
  static const Packages p = [] {
    Packages k;
    k.dir = shared_folder("globe-view-cross-tiling", [](const fs::path& dir) {
      auto at = [&](const std::string& name) { return (dir / name).string(); };
      std::ofstream csv(dir / "places.csv");
      csv << "name,lon,lat,count\n";
      for (int lat = -60; lat <= 80; lat += 20)
        for (int lon = -170; lon <= 170; lon += 20)
          csv << "p" << lon << "_" << lat << "," << lon << "," << lat << ",1\n";
      csv.close();
      const std::string etopo = sample("etopo20.tif").string();
      std::vector<std::string> steps = {
          "gdal_contour -q -i 1000 -a elev " + etopo + " " + at("c1000.shp"),
          // The reference ground for layers without terrain: zero heights.
          "gdal_create -q -of GTiff -ot Int16 -outsize 1080 540 -burn 0 -a_srs EPSG:4326 "
          "-a_ullr -180 90 180 -90 " +
              at("zero.tif"),
          tiler() + " terrain -q --tiling geodetic " + at("zero.tif") + " -o " +
              at("zero_geodetic.mbtiles")};
      for (const std::string t : {"geodetic", "webmercator"}) {
        steps.push_back(tiler() + " terrain -q --tiling " + t + " " + etopo + " -o " +
                        at("etopo_" + t + ".mbtiles"));
        steps.push_back(vectorize() + " lines -q --tiling " + t + " " + at("c1000.shp") + " -o " +
                        at("c1000_" + t + ".mbtiles") + " --style 'c1000:color=#ff0000,width=1px'");
        steps.push_back(vectorize() + " points -q --tiling " + t + " " + at("places.csv") +
                        " --xy lon,lat --fields count --merge-px 0 -o " +
                        at("places_" + t + ".mbtiles"));
      }
      return run_all(steps, dir);
    });
    return k;
  }();
  return p;
}

// A pixel of the layer `kind`: a red contour (c1000), or a chart (places):
// coloured, unlike the grey relief and the sky.
bool layer_pixel(const std::string& kind, const uint8_t* p) {
  if (kind == "c1000") return int(p[0]) - int(p[1]) > 60;
  const int lo = std::min({int(p[0]), int(p[1]), int(p[2])}),
            hi = std::max({int(p[0]), int(p[1]), int(p[2])});
  return !is_sky(p) && hi - lo > 40;
}

std::string other(const std::string& tiling) {
  return tiling == "geodetic" ? "webmercator" : "geodetic";
}

struct Case {
  const char* name;
  const char* terrain;  // tiling of the terrain (and of the reference layer)
  const char* camera;
};

class CrossTiling : public ::testing::TestWithParam<Case> {
 protected:
  // The layer `kind` (c1000 or places) in the terrain's tiling and in the
  // other one, drawn over the terrain; the marked pixels of both pictures.
  void draw_both(const std::string& kind, std::vector<bool>& same, std::vector<bool>& crossed) {
    const Case& c = GetParam();
    const std::string terrain = packages().at("etopo_" + std::string(c.terrain) + ".mbtiles");
    const std::string base = viewer() +
                             " --platform osmesa --globe --size 480x270 --camera=" + c.camera +
                             " " + terrain + " ";
    const std::string a = (dir_ / "same.png").string(), b = (dir_ / "crossed.png").string();
    ASSERT_TRUE(run_all(
        {base + packages().at(kind + "_" + c.terrain + ".mbtiles") + " --snapshot " + a,
         base + packages().at(kind + "_" + other(c.terrain) + ".mbtiles") + " --snapshot " + b},
        dir_.path()));
    auto pick = [&](const uint8_t* p) { return layer_pixel(kind, p); };
    same = pixels_where(a, w_, h_, pick);
    int w = 0, h = 0;
    crossed = pixels_where(b, w, h, pick);
    ASSERT_EQ(w, w_);
  }
  void expect_close(const std::string& what, const std::vector<bool>& same,
                    const std::vector<bool>& crossed, size_t at_least) {
    size_t ns = 0, nc = 0;
    const double sc = near_share(same, crossed, w_, h_, ns),
                 cs = near_share(crossed, same, w_, h_, nc);
    std::printf("%s, %s: %zu pixels, %.1f %% near the crossed ones; %zu crossed, %.1f %% near\n",
                GetParam().name, what.c_str(), ns, 100 * sc, nc, 100 * cs);
    EXPECT_GE(ns, at_least) << "hardly any " << what << " drawn";
    EXPECT_GE(sc, 0.97) << what;
    EXPECT_GE(cs, 0.97) << what;
  }

  TempDir dir_;
  int w_ = 0, h_ = 0;
};

TEST_P(CrossTiling, LinesLieOnTheSameTilingsLines) {
  std::vector<bool> same, crossed;
  draw_both("c1000", same, crossed);
  expect_close("contour", same, crossed, size_t(w_) * h_ / 100);
}

TEST_P(CrossTiling, ChartsStandWhereTheSameTilingsStand) {
  std::vector<bool> same, crossed;
  draw_both("places", same, crossed);
  expect_close("chart", same, crossed, size_t(w_) * h_ / 200);
}

INSTANTIATE_TEST_SUITE_P(
    Views, CrossTiling,
    ::testing::Values(Case{"geodetic_europe_oblique", "geodetic", "10,45,5000000,0,30"},
                      Case{"geodetic_greenland_topdown", "geodetic", "-40,72,4000000,0,0"},
                      Case{"geodetic_antimeridian", "geodetic", "179.5,55,3000000,90,30"},
                      Case{"webmercator_andes_topdown", "webmercator", "-70,-25,6000000,0,0"}),
    [](const auto& info) { return std::string(info.param.name); });

// Lines in another tiling draw per pixel only: the geometry baseline and
// lifted bundles place vertices in the terrain's tiling, so they are
// refused with the way out named.
TEST(CrossTilingLines, GeometryModeIsRefusedWithAWayOut) {
  TempDir dir;
  const RunResult r = run(viewer() + " --platform osmesa --flat --size 64x64 --lines geometry " +
                              packages().at("etopo_geodetic.mbtiles") + " " +
                              packages().at("c1000_webmercator.mbtiles") + " --snapshot " +
                              (dir / "x.png").string(),
                          dir.path());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("tiled unlike the terrain"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--tiling geodetic"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "x.png"));
}

// Without terrain, lines and charts are drawn over zero heights: on the
// globe (the default for these global layers) and on the map frame, where
// they stand as over a zero terrain tiled from a GDAL-made grid.
class WithoutTerrain : public ::testing::TestWithParam<const char*> {};

TEST_P(WithoutTerrain, LayersStandAsOverAZeroTerrain) {
  const std::string kind = GetParam();
  TempDir dir;
  const std::string layer = packages().at(kind + "_geodetic.mbtiles");
  for (const std::string frame :
       {"--globe --camera=10,45,5000000,0,30", "--flat --camera=-70,-25,3000000,0,0"}) {
    const std::string base =
        viewer() + " --platform osmesa --size 480x270 " + frame + " --snapshot ";
    const std::string a = (dir / "alone.png").string(), b = (dir / "zero.png").string();
    const RunResult r = run(base + a + " " + layer, dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("no terrain given"), std::string::npos) << r.err;
    ASSERT_TRUE(run_all({base + b + " " + packages().at("zero_geodetic.mbtiles") + " " + layer},
                        dir.path()));
    auto pick = [&](const uint8_t* p) { return layer_pixel(kind, p); };
    int w = 0, h = 0, zw = 0, zh = 0;
    const std::vector<bool> alone = pixels_where(a, w, h, pick),
                            zero = pixels_where(b, zw, zh, pick);
    ASSERT_EQ(w, zw);
    size_t na = 0, nz = 0;
    const double az = near_share(alone, zero, w, h, na), za = near_share(zero, alone, w, h, nz);
    std::printf("%s %s: %zu pixels alone, %.1f %% near those over zero terrain (%zu, %.1f %%)\n",
                kind.c_str(), frame.c_str(), na, 100 * az, nz, 100 * za);
    EXPECT_GE(na, size_t(w) * h / 200) << frame;
    EXPECT_GE(az, 0.97) << frame;
    EXPECT_GE(za, 0.97) << frame;
    // The ground itself is drawn: as much of the frame is sky as over the
    // zero terrain (the globe's disc, or the whole map, is ground).
    auto sky = [](const std::string& png) {
      int sw = 0, sh = 0;
      const std::vector<uint8_t> rgb = read_rgb(png, sw, sh);
      size_t n = 0;
      for (size_t i = 0; i < size_t(sw) * sh; ++i)
        n += is_sky(&rgb[3 * i]);
      return double(n) / (double(sw) * sh);
    };
    EXPECT_NEAR(sky(a), sky(b), 0.005) << frame;
    EXPECT_LT(sky(a), 0.9) << frame;
  }
}

INSTANTIATE_TEST_SUITE_P(Layers, WithoutTerrain, ::testing::Values("c1000", "places"));

}  // namespace
