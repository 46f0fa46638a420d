// Isolines per pixel (--isolines) against gdal_contour: the same levels
// extracted by GDAL from the source DEM, made a line package and drawn at the
// same camera over the same terrain. At least 95 % of each picture's line
// pixels lie within 1.5 px (a 3 x 3 neighbourhood) of the other's, top-down
// and oblique, over a regional and a global package.
#include <gtest/gtest.h>

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

}  // namespace
