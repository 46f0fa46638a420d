// globe-view's line pass as a user runs it: real line packages over real
// terrain against expected PNGs; thin-line continuity, widths in pixels on
// flat and steep terrain, deferred and geometry modes agreeing on position;
// style files; bad input.
#include <gtest/gtest.h>

#include <gdal.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "raster_fixtures.hpp"
#include "render_fixtures.hpp"
#include "test_support.hpp"

namespace {

using namespace globe_test;

// Packages built once per build tree (shared_folder), read by every test.
struct Packages {
  fs::path dir;
  std::string jacksboro, contours, wales;
};

const Packages& packages() {
  static const Packages p = [] {
    Packages k;
    k.dir = shared_folder("globe-view-lines", [](const fs::path& dir) {
      auto at = [&](const char* name) { return (dir / name).string(); };
      return run_all({tiler() + " terrain -q " + sample("jacksboro.tif").string() + " -o " +
                          at("jacksboro.mbtiles"),
                      // Contours of the same DEM: they must lie exactly on its terrain.
                      "gdal_contour -q -i 50 -a elev " + sample("jacksboro.tif").string() + " " +
                          at("c50.shp"),
                      vectorize() + " lines -q " + at("c50.shp") + " -o " + at("contours.mbtiles") +
                          " --style 'c50:color=#8c2d04,width=1.5px'",
                      vectorize() + " lines -q " + sample("os_wales_contours.shp").string() +
                          " -o " + at("wales.mbtiles")},
                     dir);
    });
    k.jacksboro = (k.dir / "jacksboro.mbtiles").string();
    k.contours = (k.dir / "contours.mbtiles").string();
    k.wales = (k.dir / "wales.mbtiles").string();
    return k;
  }();
  return p;
}

const char* kJacksboroCamera = "--camera=-84.30,36.55,2500,30,65";
// Straight down over the os_wales contours (SS64NE: Exmoor).
const char* kWalesCamera = "--camera=-3.898,51.210,3000,0,0";

std::string style_file(const fs::path& dir, const std::string& json) {
  const fs::path p = dir / "style.json";
  std::ofstream(p) << json;
  return p.string();
}

// Renders and returns RGB pixels (w x h).
std::vector<uint8_t> render(const std::string& args, const fs::path& dir, int& w, int& h) {
  const std::string out = (dir / "r.png").string();
  const RunResult r = run(viewer() + " " + args + " --snapshot " + out, dir);
  EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
  return read_rgb(out, w, h);
}

// Per pixel: how much of the way from `bg` to pure red the pixel went (0..1).
std::vector<double> redness(const std::vector<uint8_t>& img, const std::vector<uint8_t>& bg) {
  std::vector<double> out(img.size() / 3);
  for (size_t i = 0; i < out.size(); ++i) {
    const double contrast = 255.0 - bg[3 * i] + bg[3 * i + 1] + bg[3 * i + 2];
    const double moved = double(img[3 * i]) - bg[3 * i] + bg[3 * i + 1] - img[3 * i + 1] +
                         bg[3 * i + 2] - img[3 * i + 2];
    out[i] = contrast > 1 ? std::clamp(moved / contrast, 0.0, 1.0) : 0.0;
  }
  return out;
}

TEST(ViewerLines, ContoursOverJacksboroMatchExpected) {
  TempDir dir;
  const RunResult r =
      run(viewer() + " " + packages().jacksboro + " " + packages().contours + " --snapshot " +
              (dir / "a.png").string() + " --size 320x180 " + kJacksboroCamera,
          dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_image((dir / "a.png").string(), "jacksboro_contours");
}

TEST(ViewerLines, StyleFileCasingAndDashesMatchExpected) {
  TempDir dir;
  const std::string style =
      style_file(dir.path(), R"({"c50": {"color": "#ffd92f", "width": 3, "casing_color": "#303030",
                     "casing_width": 1, "dash": [8, 4]}})");
  const RunResult r = run(viewer() + " " + packages().jacksboro + " " + packages().contours +
                              " --style " + style + " --snapshot " + (dir / "a.png").string() +
                              " --size 320x180 --camera=-84.25,36.60,6000,0,0",
                          dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_image((dir / "a.png").string(), "jacksboro_contours_styled");
}

// A 1 px (and a 0.5 px) contour covers the pixels along its length: every
// pixel the geometry baseline draws (1-px quads, no antialiasing) is also
// visibly coloured by the deferred pass; and the two agree on position.
TEST(ViewerLines, ThinContoursAreContinuousAndAgreeWithGeometry) {
  TempDir dir;
  // Flat terrain under the real contours, so both modes see the same surface.
  const double gt[6] = {-3.96, 0.0005, 0, 51.25, 0, -0.0005};
  write_dem((dir / "flat.tif").string(), 240, 180, gt, "EPSG:4326", GDT_Float32,
            [](int, int) { return 100.0; });
  const RunResult t = run(tiler() + " terrain -q " + (dir / "flat.tif").string() + " -o " +
                              (dir / "flat.mbtiles").string(),
                          dir.path());
  ASSERT_EQ(t.exit_code, 0) << t.err;
  const std::string base = (dir / "flat.mbtiles").string() + " " + packages().wales +
                           " --size 480x320 " + std::string(kWalesCamera);
  int w = 0, h = 0;
  const auto bg = render(base + " --lines off", dir.path(), w, h);
  for (const double width : {1.0, 0.5}) {
    const std::string style = style_file(
        dir.path(), R"({"*": {"color": "#ff0000", "width": )" + std::to_string(width) + "}}");
    const auto geo =
        redness(render(base + " --lines geometry --style " + style, dir.path(), w, h), bg);
    const auto def = redness(render(base + " --style " + style, dir.path(), w, h), bg);
    size_t track = 0, covered = 0, near = 0, strong = 0, strong_near = 0;
    auto any_within_1px = [&](const std::vector<double>& img, int x, int y, double thr) {
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx >= 0 && yy >= 0 && xx < w && yy < h && img[size_t(yy) * w + xx] > thr) return true;
        }
      return false;
    };
    for (int y = 1; y + 1 < h; ++y)
      for (int x = 1; x + 1 < w; ++x) {
        const size_t i = size_t(y) * w + x;
        if (geo[i] > 0.9) {
          ++track;
          covered += def[i] > 0.1;
          near += any_within_1px(def, x, y, 0.4);
        }
        if (def[i] > 0.6) {
          ++strong;
          strong_near += any_within_1px(geo, x, y, 0.9);
        }
      }
    ASSERT_GT(track, 3000u) << "the contours should cross the view";
    EXPECT_GE(double(covered) / track, 0.95) << width << " px: " << covered << " of " << track;
    if (width < 1) continue;  // position agreement: on the 1 px lines
    EXPECT_GE(double(near) / track, 0.98) << near << " of " << track;
    EXPECT_GE(double(strong_near) / strong, 0.98) << strong_near << " of " << strong;
  }
}

// A straight east-west line 4 px wide: its thickness across (the sum of the
// coverage down each column) is 4 px on flat terrain seen from above, and on
// a 40-degree slope seen obliquely (slope distortion correction); a width in
// metres gives the pixels the camera geometry predicts.
TEST(ViewerLines, WidthsHoldOnFlatAndSteepTerrain) {
  TempDir dir;
  // 1" cells over 0.15 x 0.15 degrees; the ramp rises northwards at 40
  // degrees over +-20 rows around the line at 45 N, flat beyond.
  const double cell = 1.0 / 3600;
  const double gt[6] = {6.925, cell, 0, 45.075, 0, -cell};
  const int n = 540, mid = 270;
  const double rise_per_row = cell * 111320.0 * std::tan(40 * std::numbers::pi / 180);
  write_dem((dir / "flat.tif").string(), n, n, gt, "EPSG:4326", GDT_Float32,
            [](int, int) { return 500.0; });
  write_dem((dir / "ramp.tif").string(), n, n, gt, "EPSG:4326", GDT_Float32,
            [&](int, int y) { return 500.0 + std::clamp(mid + 20 - y, 0, 40) * rise_per_row; });
  std::ofstream(dir / "line.geojson")
      << R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},)"
      << R"("geometry":{"type":"LineString","coordinates":[[6.9,45.0],[7.1,45.0]]}}]})";
  for (const std::string t : {"flat", "ramp"}) {
    const RunResult r = run(tiler() + " terrain -q " + (dir / (t + ".tif")).string() + " -o " +
                                (dir / (t + ".mbtiles")).string(),
                            dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const RunResult v =
      run(vectorize() + " lines -q " + (dir / "line.geojson").string() + " -o " +
              (dir / "line.mbtiles").string() + " --max-zoom 16 --style line:width=4px",
          dir.path());
  ASSERT_EQ(v.exit_code, 0) << v.err;

  // Mean thickness (px) of the line across the middle columns.
  auto thickness = [&](const std::string& terrain, const std::string& camera,
                       const std::string& width) {
    const std::string style =
        style_file(dir.path(), R"({"*": {"color": "#ff0000", "width": )" + width + "}}");
    const std::string base = (dir / (terrain + ".mbtiles")).string() + " " +
                             (dir / "line.mbtiles").string() + " --size 320x240 " + camera;
    int w = 0, h = 0;
    const auto bg = render(base + " --lines off", dir.path(), w, h);
    const auto red = redness(render(base + " --style " + style, dir.path(), w, h), bg);
    double sum = 0;
    int cols = 0;
    for (int x = w / 4; x < 3 * w / 4; ++x, ++cols)
      for (int y = 0; y < h; ++y)
        sum += red[size_t(y) * w + x];
    return sum / cols;
  };
  EXPECT_NEAR(thickness("flat", "--camera=7,45,2500,0,0", "4"), 4.0, 0.5);
  EXPECT_NEAR(thickness("flat", "--camera=7,45,2500,0,0", "1"), 1.0, 0.5);
  // Looking north at the south-facing slope: the line runs across the view.
  EXPECT_NEAR(thickness("ramp", "--camera=7,44.985,2200,0,55", "4"), 4.0, 0.5);
  EXPECT_NEAR(thickness("ramp", "--camera=7,44.985,2200,0,55", "1.5"), 1.5, 0.5);
  // 20 m seen from 2000 m above the plane: 20 * (240 / 2) / tan(22.5 deg) / 2000 px.
  const double expected_px = 20 * 120 / std::tan(22.5 * std::numbers::pi / 180) / 2000;
  const std::string metres = R"(20, "unit": "m")";
  EXPECT_NEAR(thickness("flat", "--camera=7,45,2500,0,0", metres), expected_px, 0.5);
}

TEST(ViewerLines, StatsReportTheLinePass) {
  TempDir dir;
  const RunResult r = run(viewer() + " " + packages().jacksboro + " " + packages().contours +
                              " --stats --frames 2 --size 160x90 " + kJacksboroCamera,
                          dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* key : {"\"lines\": \"deferred\"", "\"lines_ms\": ", "\"line_tiles_used\": ",
                          "\"line_bytes\": ", "\"line_budget_bytes\": "})
    EXPECT_NE(r.out.find(key), std::string::npos) << key << "\n" << r.out;
  EXPECT_EQ(r.out.find("\"line_tiles_used\": 0,"), std::string::npos) << r.out;
}

TEST(ViewerLines, CorruptLineTileWarnsAndTheFrameGoesOn) {
  TempDir dir;
  const std::string pkg = (dir / "broken.mbtiles").string();
  fs::copy_file(packages().contours, pkg);
  const RunResult s =
      run("sqlite3 " + pkg + " \"UPDATE blobs SET tile_data = randomblob(64);\"", dir.path());
  ASSERT_EQ(s.exit_code, 0) << s.err;
  const RunResult r = run(viewer() + " " + packages().jacksboro + " " + pkg +
                              " --stats --frames 1 --size 160x90 " + kJacksboroCamera,
                          dir.path());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("line tile"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the lines of its coarser or finer tiles are drawn there"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.out.find("\"broken_line_tiles\": 0"), std::string::npos) << r.out;
}

// A magic lens that shows the lines: only inside it, exactly as drawn
// everywhere; outside, the terrain alone, byte for byte.
TEST(ViewerLines, ALensShowsTheLinesOnlyInsideIt) {
  TempDir dir;
  auto shot = [&](const std::string& name, const std::string& packages) {
    const std::string png = (dir / (name + ".png")).string();
    const RunResult r =
        run(viewer() + " --platform osmesa --size 320x180 " + std::string(kJacksboroCamera) + " " +
                packages + " --snapshot " + png,
            dir.path());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    int w = 0, h = 0;
    return read_rgb(png, w, h);
  };
  const std::string t = packages().jacksboro, l = packages().contours;
  const auto plain = shot("plain", t), lines = shot("lines", t + " " + l),
             lens = shot("lens", t + " " + l + " --lens 160,110,60:lines");
  EXPECT_GT(expect_lens_frame(plain, lines, lens, 320, 180, 160, 110, 60), 10000u);
}

TEST(ViewerLines, BadInputGetsAClearError) {
  TempDir dir;
  const RunResult g = run(vectorize() + " lines -q " + sample("os_wales_contours.shp").string() +
                              " --tiling local -o " + (dir / "bng.mbtiles").string(),
                          dir.path());
  ASSERT_EQ(g.exit_code, 0) << g.err;
  std::ofstream(dir / "broken.json") << "{ not json";
  std::ofstream(dir / "unknown.json") << R"({"motorway": {"color": "#ff0000"}})";
  std::ofstream(dir / "badkey.json") << R"({"c50": {"colour": "#ff0000"}})";
  const std::string t = packages().jacksboro, l = packages().contours;
  const std::string snap = " --snapshot " + (dir / "out.png").string();
  struct Case {
    std::string args, message;
    int code;
  };
  const Case cases[] = {
      {t + " " + (dir / "bng.mbtiles").string() + snap,
       "cross between geodetic and webmercator only", 1},
      {t + " " + l + " --style " + (dir / "broken.json").string() + snap, "broken.json", 1},
      {t + " " + l + " --style " + (dir / "unknown.json").string() + snap, "no class \"motorway\"",
       1},
      {t + " " + l + " --style " + (dir / "badkey.json").string() + snap, "\"colour\"", 1},
      {t + " " + l + " --style " + (dir / "missing.json").string() + snap, "missing.json", 1},
      {t + " --style " + (dir / "unknown.json").string() + snap, "give a line package", 2},
      {t + " " + l + " " + l + snap, "two line packages", 2},
      {snap, "no package given", 2},
      {t + " " + l + " --lines wiggly" + snap, "--lines", 2},
  };
  for (const Case& c : cases) {
    const RunResult r = run(viewer() + " " + c.args, dir.path());
    EXPECT_EQ(r.exit_code, c.code) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
  }
  EXPECT_FALSE(fs::exists(dir / "out.png"));
}

}  // namespace
