// globe-view's charts (docs/viewer.md "Charts") as a user runs them: US
// airports' flights by region over the etopo20 globe as pies seen from above
// and as columns in perspective, legend included, against expected PNGs;
// one chart measured in its PNG (slice angles and bar heights within one
// pixel of the values); picking; depth against the terrain; bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <numbers>

#include "point_fixtures.hpp"
#include "raster_fixtures.hpp"
#include "render_fixtures.hpp"
#include "test_paths.hpp"
#include "test_support.hpp"

namespace {

using namespace globe_test;

// Packages built once per build tree (shared_folder), read by every test.
struct Packages {
  fs::path dir;
  std::string world, flights, flat, one, signed_points;
};

const std::vector<std::string> kRegions{"west", "midwest", "south", "northeast", "other"};

const Packages& packages() {
  static const Packages p = [] {
    Packages k;
    k.dir = shared_folder("globe-view-charts", [](const fs::path& dir) {
      auto at = [&](const char* name) { return (dir / name).string(); };
      // One place over a flat plain (100 m) for the measurements.
      const double gt[6] = {10, 1.0 / 256, 0, 46, 0, -1.0 / 256};
      write_dem(at("flat.tif"), 256, 256, gt, "EPSG:4326", GDT_Float32,
                [](int, int) { return 100.0; });
      write_places_csv(at("one.csv"), {"a", "b", "c", "d"}, {{"only", 10.5, 45.5, {1, 2, 3, 6}}});
      write_places_csv(at("signed.csv"), {"a"}, {{"minus", 10.5, 45.5, {-1}}});
      return run_all({tiler() + " terrain -q " + sample("etopo20.tif").string() +
                          " --max-zoom 4 -o " + at("world.mbtiles"),
                      vectorize() + " points -q " + sample("us_airport_flights.csv").string() +
                          " --xy longitude,latitude --fields west,midwest,south,northeast,other "
                          "--label-field iata -o " +
                          at("flights.mbtiles"),
                      tiler() + " terrain -q " + at("flat.tif") + " -o " + at("flat.mbtiles"),
                      vectorize() + " points -q " + at("one.csv") +
                          " --xy lon,lat --fields a,b,c,d --max-zoom 8 -o " + at("one.mbtiles"),
                      vectorize() + " points -q " + at("signed.csv") +
                          " --xy lon,lat --fields a --signed -o " + at("signed.mbtiles")},
                     dir);
    });
    k.world = (k.dir / "world.mbtiles").string();
    k.flights = (k.dir / "flights.mbtiles").string();
    k.flat = (k.dir / "flat.mbtiles").string();
    k.one = (k.dir / "one.mbtiles").string();
    k.signed_points = (k.dir / "signed.mbtiles").string();
    return k;
  }();
  return p;
}

std::string write_style(const fs::path& dir, const std::string& json) {
  const fs::path path = dir / "chart-style.json";
  std::ofstream(path) << json;
  return path.string();
}

// The single chart over the plain, straight down, 200 px, no outline nor
// legend, primary colours.
std::vector<uint8_t> render_one(const std::string& kind, int& w, int& h) {
  const Packages& k = packages();
  TempDir dir;
  const std::string style =
      write_style(dir.path(),
                  R"({"colors": {"a": "#ff0000", "b": "#00ff00", "c": "#0000ff", "d": "#ffff00"},
          "min_px": 200, "max_px": 200, "outline_px": 0, "legend": false})");
  const std::string out = (dir / "one.png").string();
  const RunResult r =
      run(viewer() + " " + k.flat + " " + k.one + " --chart " + kind + " --chart-style " + style +
              " --size 400x400 --camera=10.5,45.5,6000,0,0 --snapshot " + out,
          dir.path());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return read_rgb(out, w, h);
}

// Which of the four primary colours a pixel is (-1: none).
int colour_of(const uint8_t* p) {
  const int colours[4][3] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {255, 255, 0}};
  for (int c = 0; c < 4; ++c)
    if (std::abs(p[0] - colours[c][0]) < 40 && std::abs(p[1] - colours[c][1]) < 40 &&
        std::abs(p[2] - colours[c][2]) < 40)
      return c;
  return -1;
}

}  // namespace

TEST(ViewerCharts, PiesOverTheGlobeFromAboveMatchExpected) {
  const Packages& k = packages();
  TempDir dir;
  const std::string out = (dir / "pies.png").string();
  const RunResult r = run(viewer() + " " + k.world + " " + k.flights +
                              " --size 480x300 --camera=-97,39,3000000,0,0 --snapshot " + out,
                          dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_image(out, "us_flights_pies");
}

TEST(ViewerCharts, ColumnsInPerspectiveMatchExpected) {
  const Packages& k = packages();
  TempDir dir;
  const std::string out = (dir / "columns.png").string();
  const RunResult r =
      run(viewer() + " " + k.world + " " + k.flights +
              " --chart column --exaggeration 20 --size 480x300 --camera=-90,27,900000,0,55 "
              "--snapshot " +
              out,
          dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_image(out, "us_flights_columns");
}

// Values 1, 2, 3, 6 of a 200 px pie: slices of 30, 60, 90 and 180 degrees,
// clockwise from the top. Each edge found on a circle of 80 px lies within
// one pixel (at the rim) of where the values put it; the pie's area gives
// its diameter.
TEST(ViewerCharts, PieSliceAnglesMatchTheValuesWithinAPixel) {
  int w = 0, h = 0;
  const auto rgb = render_one("pie", w, h);
  ASSERT_EQ(w, 400);
  double cx = 0, cy = 0, n = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (colour_of(&rgb[(size_t(y) * w + x) * 3]) >= 0) cx += x, cy += y, ++n;
  ASSERT_GT(n, 1000);
  cx /= n, cy /= n;
  const double radius = std::sqrt(n / std::numbers::pi);
  EXPECT_NEAR(radius, 100, 1.0);
  // Walk a circle of 80 px clockwise from the top; note where the colour
  // changes.
  std::vector<std::pair<double, int>> edges;  // angle (degrees), colour after
  int last = -2;
  for (int step = 0; step <= 3600; ++step) {
    const double a = step * 0.1 * std::numbers::pi / 180;
    const int x = int(std::lround(cx + 80 * std::sin(a))),
              y = int(std::lround(cy - 80 * std::cos(a)));
    const int c = colour_of(&rgb[(size_t(y) * w + x) * 3]);
    if (c != last && last != -2) edges.emplace_back(step * 0.1, c);
    last = c;
  }
  // Edges at 30 (to b), 90 (to c), 180 (to d) and 360 (to a).
  const std::map<int, double> expected{{1, 30}, {2, 90}, {3, 180}, {0, 360}};
  ASSERT_EQ(edges.size(), 4u);
  const double one_px_deg = 180 / (std::numbers::pi * radius);
  for (const auto& [angle, colour] : edges) {
    ASSERT_TRUE(expected.count(colour)) << "an edge into an unexpected colour at " << angle;
    const double off = std::fmod(angle - expected.at(colour) + 540, 360) - 180;  // wraps at 0
    EXPECT_LE(std::abs(off), one_px_deg + 0.1) << "colour " << colour << " at " << angle;
  }
}

// Bars of values 1, 2, 3, 6 with the tallest 200 px: 33.3, 66.7, 100 and
// 200 px tall, on one baseline, within one pixel.
TEST(ViewerCharts, BarHeightsMatchTheValuesWithinAPixel) {
  int w = 0, h = 0;
  const auto rgb = render_one("bar", w, h);
  ASSERT_EQ(w, 400);
  for (int c = 0; c < 4; ++c) {
    int top = h, bottom = -1, columns = 0;
    for (int x = 0; x < w; ++x) {
      bool any = false;
      for (int y = 0; y < h; ++y)
        if (colour_of(&rgb[(size_t(y) * w + x) * 3]) == c) {
          top = std::min(top, y);
          bottom = std::max(bottom, y);
          any = true;
        }
      columns += any;
    }
    ASSERT_GT(columns, 2) << "bar " << c << " not found";
    const double values[4] = {1, 2, 3, 6};
    EXPECT_NEAR(bottom - top + 1, 200 * values[c] / 6, 1.0) << "bar " << c;
    EXPECT_NEAR(bottom, 200 - 1, 2.0) << "bar " << c << ": the baseline is the place";
  }
}

// --pick names the place under a pixel and its values; nothing elsewhere.
TEST(ViewerCharts, PickNamesThePlaceUnderAPixel) {
  const Packages& k = packages();
  TempDir dir;
  const RunResult hit = run(viewer() + " " + k.flat + " " + k.one +
                                " --size 400x400 --camera=10.5,45.5,6000,0,0 --pick 200,200",
                            dir.path());
  ASSERT_EQ(hit.exit_code, 0) << hit.err;
  EXPECT_EQ(hit.out, "place 1: a 1, b 2, c 3, d 6\n");
  const RunResult miss = run(viewer() + " " + k.flat + " " + k.one +
                                 " --size 400x400 --camera=10.5,45.5,6000,0,0 --pick 5,5",
                             dir.path());
  EXPECT_EQ(miss.out, "\n");
  // With a label field: the airport's code.
  const RunResult airport = run(viewer() + " " + k.world + " " + k.flights +
                                    " --size 480x300 --camera=-84.43,33.64,300000,0,0 "
                                    "--chart-depth top --pick 240,150",
                                dir.path());
  ASSERT_EQ(airport.exit_code, 0) << airport.err;
  EXPECT_EQ(airport.out.rfind("ATL", 0), 0u) << airport.out;
}

// A hill between the eye and a place hides its chart (depth against the
// terrain); --chart-depth top draws it anyway.
TEST(ViewerCharts, TheTerrainHidesChartsBehindItUnlessOnTop) {
  const Packages& k = packages();
  TempDir dir;
  // A 3 km wall across the plain's south, the place north of it, seen from
  // the south at a low angle.
  const std::string dem = (dir / "wall.tif").string();
  const double gt[6] = {10, 1.0 / 256, 0, 46, 0, -1.0 / 256};
  write_dem(dem, 256, 256, gt, "EPSG:4326", GDT_Float32,
            [](int, int y) { return y > 170 && y < 180 ? 3000.0 : 100.0; });
  const std::string terrain = (dir / "wall.mbtiles").string();
  ASSERT_TRUE(build_terrain("", dem, terrain, dir.path()));
  auto count = [&](const std::string& extra) {
    const std::string out = (dir / "wall.png").string();
    const std::string style =
        write_style(dir.path(), R"({"colors": {"a": "#ff0000", "b": "#00ff00", "c": "#0000ff",
                        "d": "#ffff00"}, "legend": false})");
    const RunResult r =
        run(viewer() + " " + terrain + " " + k.one + " --chart-style " + style +
                " --size 320x200 --camera=10.5,45.15,1200,0,84 --snapshot " + out + " " + extra,
            dir.path());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    int w = 0, h = 0;
    const auto rgb = read_rgb(out, w, h);
    size_t n = 0;
    for (size_t i = 0; i + 2 < rgb.size(); i += 3)
      n += colour_of(&rgb[i]) >= 0;
    return n;
  };
  EXPECT_EQ(count(""), 0u) << "the chart shows through the wall";
  EXPECT_GT(count("--chart-depth top"), 200u) << "on top, the chart is drawn";
}

TEST(ViewerCharts, BadInputIsAClearError) {
  const Packages& k = packages();
  TempDir dir;
  auto expect = [&](const std::string& args, int code, const std::string& says) {
    const RunResult r = run(
        viewer() + " " + args + " --size 64x64 --snapshot " + (dir / "x.png").string(), dir.path());
    EXPECT_EQ(r.exit_code, code) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << args << "\n" << r.err;
  };
  expect(k.flat + " " + k.signed_points, 2, "holds negative values (built with --signed)");
  expect(k.flat + " " + k.signed_points + " --chart stacked", 2, "--chart stacked");
  expect(k.flat + " --chart bar", 2, "give a point package too");
  expect(k.flat + " " + k.one + " " + k.one, 2, "two point packages");
  expect(k.flat + " " + k.one + " --chart donut", 2, "--chart: unknown kind 'donut'");
  const std::string bad = write_style(dir.path(), R"({"colors": {"e": "#ff0000"}})");
  expect(k.flat + " " + k.one + " --chart-style " + bad, 1,
         "names field 'e', which the package does not have (its fields: a, b, c, d)");
  const std::string typo = write_style(dir.path(), R"({"max_pix": 20})");
  expect(k.flat + " " + k.one + " --chart-style " + typo, 1, "unknown key \"max_pix\"");
  // Bars and columns draw signed values.
  const RunResult ok = run(viewer() + " " + k.flat + " " + k.signed_points +
                               " --chart bar --size 64x64 --snapshot " + (dir / "b.png").string(),
                           dir.path());
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

// The window under a virtual X server: the pointer over Atlanta's chart
// names the airport and its flights in the title.
TEST(ViewerChartsWindow, TheTitleNamesThePlaceUnderThePointer) {
  const Packages& k = packages();
  TempDir dir;
  const RunResult w =
      run("xvfb-run -a -s '-screen 0 640x480x24' " + globe_test::paths::test_data_dir() +
              "/window/hover_title.sh " + dir.path().string() + " 160 90 " + viewer() +
              " --platform glfw --size 320x180 --chart-depth top "
              "--camera=-84.43,33.64,300000,0,0 " +
              k.world + " " + k.flights,
          dir.path());
  ASSERT_EQ(w.exit_code, 0) << w.err << read_file(dir / "viewer.stderr");
  EXPECT_NE(w.out.find("ATL: west "), std::string::npos) << w.out;
  EXPECT_NE(w.out.find("northeast "), std::string::npos) << w.out;
}

// --chart-thinning drops the charts whose centre falls on a larger chart:
// fewer are drawn, and those left do not cover each other's centres.
TEST(ViewerCharts, ThinningDropsChartsOnLargerOnes) {
  const Packages& k = packages();
  TempDir dir;
  auto stats = [&](const std::string& extra) {
    const RunResult r =
        run(viewer() + " " + k.world + " " + k.flights +
                " --size 480x300 --camera=-84,36,2500000,0,0 --stats --frames 1 " + extra,
            dir.path());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return std::pair(integer_after(r.out, "\"charts\":"),
                     integer_after(r.out, "\"charts_thinned\":"));
  };
  const auto [all, none] = stats("");
  const auto [kept, thinned] = stats("--chart-thinning");
  EXPECT_EQ(none, 0);
  EXPECT_GT(thinned, 0) << "no chart of the east coast fell on another";
  EXPECT_EQ(kept + thinned, all);
}

// Broken point tiles (issue 55): the flights' two coarsest zooms made
// unreadable; over the US, where the view wants them, the charts of their
// children are drawn (before: none at all), and the broken tiles are named.
TEST(ViewerCharts, BrokenPointTilesAreDrawnFromTheirChildren) {
  const Packages& k = packages();
  TempDir dir;
  const std::string pkg = (dir / "broken.mbtiles").string();
  fs::copy_file(k.flights, pkg);
  const RunResult s = run("sqlite3 " + pkg +
                              " \"UPDATE blobs SET tile_data = randomblob(100) WHERE blob_id IN "
                              "(SELECT blob_id FROM map WHERE zoom_level <= 1);\"",
                          dir.path());
  ASSERT_EQ(s.exit_code, 0) << s.err;
  const std::string style = write_style(dir.path(), R"({"legend": false})");
  auto shot = [&](const std::string& name, const std::string& points, std::string* err = nullptr) {
    const std::string png = (dir / (name + ".png")).string();
    const RunResult r = run(viewer() + " --platform osmesa " + k.world + " " +
                                (points.empty() ? "" : points + " --chart-style " + style) +
                                " --size 240x150 --camera=-97,39,3000000,0,0 --snapshot " + png,
                            dir.path());
    EXPECT_EQ(r.exit_code, 0) << name << "\n" << r.err;
    if (err) *err = r.err;
    int w = 0, h = 0;
    return r.exit_code == 0 ? read_rgb(png, w, h) : std::vector<uint8_t>(240 * 150 * 3);
  };
  std::string err;
  const auto bare = shot("bare", ""), intact = shot("intact", k.flights),
             broken = shot("broken", pkg, &err);
  auto chart_pixels = [&](const std::vector<uint8_t>& rgb) {
    size_t n = 0;
    for (size_t i = 0; i < rgb.size(); i += 3)
      n += std::abs(rgb[i] - bare[i]) + std::abs(rgb[i + 1] - bare[i + 1]) +
               std::abs(rgb[i + 2] - bare[i + 2]) >
           30;
    return n;
  };
  EXPECT_NE(err.find("broken.mbtiles: point tile 0/0/0"), std::string::npos) << err;
  EXPECT_NE(err.find("the charts of its finer or coarser tiles are drawn there"),
            std::string::npos);
  EXPECT_GT(chart_pixels(intact), 300u);
  EXPECT_GE(chart_pixels(broken), chart_pixels(intact) / 2) << err;
}
