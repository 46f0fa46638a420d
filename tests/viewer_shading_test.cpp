// globe-view's shading modes as a user runs them: the elevation ramp spans
// the data's real heights (sea and land on a global relief grid, lowlands
// to peaks over the Himalaya), gdaldem colour files, and clear errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "render_fixtures.hpp"
#include "test_support.hpp"

namespace {

using namespace globe_test;

struct Shaded {
  fs::path dir;
  std::string global, himalaya;
};

const Shaded& packages() {
  static const Shaded s = [] {
    Shaded k;
    k.dir = shared_folder("globe-view-shading", [](const fs::path& dir) {
      auto at = [&](const char* name) { return (dir / name).string(); };
      const std::string etopo = sample("etopo20.tif").string();
      return run_all(
          {tiler() + " terrain -q --tiling geodetic " + etopo + " -o " + at("etopo.mbtiles"),
           // The Himalaya: etopo20 cut to 70..100 E, 25..40 N (28 m to 6229 m).
           "gdal_translate -q -projwin 70 40 100 25 " + etopo + " " + at("himalaya.tif"),
           tiler() + " terrain -q " + at("himalaya.tif") + " -o " + at("himalaya.mbtiles")},
          dir);
    });
    k.global = (k.dir / "etopo.mbtiles").string();
    k.himalaya = (k.dir / "himalaya.mbtiles").string();
    return k;
  }();
  return s;
}

RunResult view(const std::string& args, const fs::path& dir) {
  return run(viewer() + " --platform osmesa " + args, dir);
}

bool blue(const uint8_t* p) {
  return p[2] > p[0] + 40 && p[2] > p[1];
}
bool green(const uint8_t* p) {
  return p[1] > p[0] + 15 && p[1] > p[2] + 15;
}
bool pale(const uint8_t* p) {  // the top of the ramp: greys to white
  const int lo = std::min({p[0], p[1], p[2]}), hi = std::max({p[0], p[1], p[2]});
  return lo > 140 && hi - lo < 50;
}
bool brown(const uint8_t* p) {
  return p[0] > p[1] + 20 && p[1] > p[2] + 10;
}

TEST(ViewerShading, ElevationOnAGlobalGridShowsSeaAndLand) {
  TempDir dir;
  const std::string snap = (dir / "a.png").string();
  const RunResult r = view(packages().global +
                               " --globe --fit --shading elevation --size 320x180"
                               " --snapshot " +
                               snap,
                           dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int w, h;
  const auto rgb = read_rgb(snap, w, h);
  Census c;
  // The disc centred on 0 N 0 E: about two thirds ocean (the Atlantic and
  // the Gulf of Guinea), the rest Africa and Europe.
  const double sea = c.fraction(rgb, blue), land = c.fraction(rgb, green) + c.fraction(rgb, brown);
  EXPECT_GT(c.terrain, 15000u);
  EXPECT_GT(sea, 0.45) << "sea pixels";
  EXPECT_LT(sea, 0.85) << "sea pixels";
  EXPECT_GT(land, 0.12) << "land pixels";
  expect_image(snap, "globe_etopo_elevation");
}

TEST(ViewerShading, ElevationOverTheHimalayaSpansLowlandsToPeaks) {
  TempDir dir;
  const std::string snap = (dir / "a.png").string();
  const RunResult r = view(packages().himalaya +
                               " --fit --shading elevation --size 320x180"
                               " --snapshot " +
                               snap,
                           dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int w, h;
  const auto rgb = read_rgb(snap, w, h);
  Census c;
  // The Ganges plain and the Tarim basin's rim are low, Tibet is above
  // 4500 m: both ends of the ramp must show.
  EXPECT_GT(c.fraction(rgb, green), 0.15) << "lowland pixels";
  EXPECT_GT(c.fraction(rgb, pale), 0.05) << "peak pixels (Tibet)";
  EXPECT_GT(c.fraction(rgb, brown), 0.05) << "mid-height pixels";
  expect_image(snap, "himalaya_elevation");
}

TEST(ViewerShading, ColourFileAndRangeOptionsColourTheRamp) {
  TempDir dir;
  std::ofstream(dir / "rb.txt") << "0% 255 0 0\n100% 0 0 255\nnv 0 0 0 0\n";
  const std::string snap = (dir / "a.png").string();
  RunResult r = view(packages().himalaya + " --fit --shading elevation --size 160x90 --colormap " +
                         (dir / "rb.txt").string() + " --snapshot " + snap,
                     dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int w, h;
  auto rgb = read_rgb(snap, w, h);
  Census c;
  EXPECT_EQ(c.fraction(rgb, [](const uint8_t* p) { return p[1] > 8; }), 0.0) << "no green";
  EXPECT_GT(c.fraction(rgb, [](const uint8_t* p) { return p[0] > p[2] + 60; }), 0.1) << "red";
  EXPECT_GT(c.fraction(rgb, [](const uint8_t* p) { return p[2] > p[0] + 60; }), 0.1) << "blue";
  // --height-range: the gray ramp over 0..1 m makes all this land white
  // (times the hillshade factor: at least 0.55 of 255).
  r = view(packages().himalaya +
               " --fit --shading elevation --size 160x90 --colormap gray"
               " --height-range 0,1 --snapshot " +
               snap,
           dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  rgb = read_rgb(snap, w, h);
  EXPECT_EQ(c.fraction(rgb, [](const uint8_t* p) { return p[0] < 135; }), 0.0);
}

TEST(ViewerShading, BadRampOptionsAreClearErrors) {
  TempDir dir;
  const std::string pkg = packages().himalaya, snap = " --snapshot " + (dir / "a.png").string();
  RunResult r = view(pkg + " --colormap " + (dir / "none.txt").string() + snap, dir.path());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("none.txt: cannot read the colour file"), std::string::npos) << r.err;
  std::ofstream(dir / "bad.txt") << "0 0 0 0\n100 red green\n";
  r = view(pkg + " --colormap " + (dir / "bad.txt").string() + snap, dir.path());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("bad.txt:2:"), std::string::npos) << r.err;
  r = view(pkg + " --height-range 5,1" + snap, dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--height-range: MAX must be above MIN"), std::string::npos) << r.err;
  r = view(pkg + " --height-percentile 50" + snap, dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_FALSE(fs::exists(dir / "a.png"));
}

}  // namespace
