// Isolines per pixel (--isolines) against gdal_contour: the same levels
// extracted by GDAL from the source DEM, made a line package and drawn at the
// same camera over the same terrain. At least 95 % of each picture's line
// pixels lie within 1.5 px (a 3 x 3 neighbourhood) of the other's, top-down
// and oblique, over a regional and a global package.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "render_fixtures.hpp"
#include "test_support.hpp"

namespace {

using namespace globe_test;

struct Packages {
  fs::path dir;
  std::string terrain(const char* name) const { return (dir / name).string(); }
};

// jacksboro (webmercator) with 50 m contours, etopo20 (geodetic) with 1000 m
// ones, each as a line package drawn in pure red, 1 px wide.
const Packages& packages() {
  static const Packages p = [] {
    Packages k;
    k.dir = shared_folder("globe-view-isolines", [](const fs::path& dir) {
      auto at = [&](const char* name) { return (dir / name).string(); };
      const std::string jacksboro = sample("jacksboro.tif").string(),
                        etopo = sample("etopo20.tif").string();
      return run_all(
          {tiler() + " terrain -q " + jacksboro + " -o " + at("jacksboro.mbtiles"),
           "gdal_contour -q -i 50 -a elev " + jacksboro + " " + at("c50.shp"),
           vectorize() + " lines -q " + at("c50.shp") + " -o " + at("c50.mbtiles") +
               " --style 'c50:color=#ff0000,width=1px'",
           tiler() + " terrain -q --tiling geodetic " + etopo + " -o " + at("etopo.mbtiles"),
           "gdal_contour -q -i 1000 -a elev " + etopo + " " + at("c1000.shp"),
           vectorize() + " lines -q --tiling geodetic " + at("c1000.shp") + " -o " +
               at("c1000.mbtiles") + " --style 'c1000:color=#ff0000,width=1px'"},
          dir);
    });
    return k;
  }();
  return p;
}

struct Case {
  const char* name;
  const char* terrain;
  const char* lines;
  const char* interval;
  const char* camera;
};

class Isolines : public ::testing::TestWithParam<Case> {};

TEST_P(Isolines, LieOnGdalContours) {
  const Case& c = GetParam();
  TempDir dir;
  const std::string terrain = packages().terrain(c.terrain), lines = packages().terrain(c.lines);
  const std::string base = viewer() + " --platform osmesa --size 480x270 --camera=" + c.camera;
  const std::string ours = (dir / "isolines.png").string(), ref = (dir / "contours.png").string();
  ASSERT_TRUE(run_all({base + " " + terrain + " --isolines " + c.interval +
                           " --isoline-color '#ff0000' --snapshot " + ours,
                       base + " " + terrain + " " + lines + " --snapshot " + ref},
                      dir.path()));
  int w = 0, h = 0, rw = 0, rh = 0;
  const std::vector<bool> a = red_pixels(ours, w, h), b = red_pixels(ref, rw, rh);
  ASSERT_EQ(w, rw);
  size_t na = 0, nb = 0;
  const double ab = near_share(a, b, w, h, na), ba = near_share(b, a, w, h, nb);
  std::printf(
      "%s: %zu isoline pixels, %.1f %% near a contour; %zu contour pixels, %.1f %% near "
      "an isoline\n",
      c.name, na, 100 * ab, nb, 100 * ba);
  EXPECT_GT(na, size_t(w) * h / 100) << "hardly any isolines drawn";
  EXPECT_GE(ab, 0.95);
  EXPECT_GE(ba, 0.95);
}

INSTANTIATE_TEST_SUITE_P(Views, Isolines,
                         ::testing::Values(Case{"regional_top_down", "jacksboro.mbtiles",
                                                "c50.mbtiles", "50", "-84.2458,36.5896,12000,0,0"},
                                           Case{"regional_oblique", "jacksboro.mbtiles",
                                                "c50.mbtiles", "50", "-84.30,36.55,4000,30,55"},
                                           Case{"global_top_down", "etopo.mbtiles", "c1000.mbtiles",
                                                "1000", "86.9,27.9,3000000,0,0"},
                                           Case{"global_oblique", "etopo.mbtiles", "c1000.mbtiles",
                                                "1000", "-70,-25,6000000,0,20"}),
                         [](const ::testing::TestParamInfo<Case>& i) {
                           return std::string(i.param.name);
                         });

TEST(IsolineOptions, BadValuesAreUsageErrors) {
  TempDir dir;
  for (const char* bad :
       {"--isolines 0", "--isolines x", "--isolines 50,0", "--isoline-color red"}) {
    const RunResult r = run(viewer() + " " + packages().terrain("jacksboro.mbtiles") +
                                " --snapshot " + (dir / "x.png").string() + " " + bad,
                            dir.path());
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.err;
  }
}

// --isolines-of slope on a paraboloid z = a r^2 (a = 0.0005 / m, 10 m cells,
// UTM): its slope is atan(2 a r), so the isolines every 10 degrees are
// circles around the apex at r_k = tan(10 k deg) / (2 a). Seen straight down
// from 60 km through a 5 degree field of view (nearly orthographic), the
// circles' radii in pixels follow tan(10 k deg) with the scale this camera
// gives: a closed-form reference, no shared code.
TEST(IsolinesOf, SlopeIsolinesAreTheParaboloidsCircles) {
  TempDir dir;
  const int n = 401;
  const double cell = 10, a = 0.0005;
  {
    std::ofstream asc(dir / "p.asc");
    asc << "ncols " << n << "\nnrows " << n << "\nxllcorner 500000\nyllcorner 4000000\ncellsize "
        << cell << "\n";
    for (int j = 0; j < n; ++j) {
      const double y = (n - 1 - j) * cell - 2000;
      for (int i = 0; i < n; ++i) {
        const double x = i * cell - 2000;
        asc << (i ? " " : "") << a * (x * x + y * y);
      }
      asc << "\n";
    }
    std::ofstream(dir / "p.prj") << "EPSG:32616";
  }
  // The apex: the centre of cell (200, 200), easting 502005, northing 4002005.
  const std::string pkg = (dir / "p.mbtiles").string(), png = (dir / "s.png").string();
  ASSERT_TRUE(run_all(
      {tiler() + " terrain -q --s_srs EPSG:32616 " + (dir / "p.asc").string() + " -o " + pkg},
      dir.path()));
  const RunResult apex =
      run("echo 502005 4002005 | gdaltransform -s_srs EPSG:32616 -t_srs EPSG:4326", dir.path());
  double lon = 0, lat = 0;
  ASSERT_EQ(std::sscanf(apex.out.c_str(), "%lf %lf", &lon, &lat), 2) << apex.out << apex.err;
  char camera[128];
  std::snprintf(camera, sizeof camera, "--camera=%.7f,%.7f,60000,0,0", lon, lat);
  const RunResult r =
      run(viewer() + " --platform osmesa --size 480x270 --fov 5 " + camera + " " + pkg +
              " --isolines 10 --isolines-of slope --isoline-color '#ff0000'" + " --snapshot " + png,
          dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int w = 0, h = 0;
  const std::vector<bool> red = red_pixels(png, w, h);
  // Distances from the apex (the frame's centre) of the isoline pixels
  // inside 1.5 km (the DEM's own edge draws spurious levels further out).
  const double m_per_px = 2 * 60000 * std::tan(2.5 * M_PI / 180) / h;
  std::vector<double> d;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (red[size_t(y) * w + x]) {
        const double dist = std::hypot(x + 0.5 - w / 2.0, y + 0.5 - h / 2.0);
        if (dist * m_per_px < 1500) d.push_back(dist);
      }
  ASSERT_GT(d.size(), 500u) << "hardly any isolines";
  auto share_on_circles = [&](double r1) {
    size_t on = 0;
    for (double v : d) {
      double best = 1e9;
      for (int k = 1; k <= 8; ++k)
        best = std::min(
            best, std::abs(v - r1 * std::tan(10 * k * M_PI / 180) / std::tan(10 * M_PI / 180)));
      on += best <= 1.5;
    }
    return double(on) / double(d.size());
  };
  // The first circle's radius in pixels: the best fit, and the camera's.
  double fit = 0, fit_share = 0;
  for (double r1 = 2; r1 < 40; r1 += 0.05)
    if (const double s = share_on_circles(r1); s > fit_share) fit = r1, fit_share = s;
  const double expected = std::tan(10 * M_PI / 180) / (2 * a) / m_per_px;
  std::printf(
      "slope isolines: %zu pixels, %.1f %% on circles of radius ratio tan(10k)/tan(10) "
      "(first %.2f px; the camera gives %.2f px)\n",
      d.size(), 100 * fit_share, fit, expected);
  EXPECT_GE(fit_share, 0.95);
  EXPECT_NEAR(fit, expected, 0.05 * expected);
}

TEST(IsolinesOf, FlowNeedsAnAnalysisPackage) {
  TempDir dir;
  const RunResult r =
      run(viewer() + " --platform osmesa " + packages().terrain("jacksboro.mbtiles") +
              " --isolines 1 --isolines-of flow --snapshot " + (dir / "x.png").string(),
          dir.path());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--isolines-of flow draws the flow_accumulation layer"), std::string::npos)
      << r.err;
}

}  // namespace
