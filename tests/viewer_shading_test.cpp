// globe-view's shading modes as a user runs them: the elevation ramp spans
// the data's real heights (sea and land on a global relief grid, lowlands
// to peaks over the Himalaya), gdaldem colour files, and clear errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "raster_fixtures.hpp"
#include "render_fixtures.hpp"
#include "test_paths.hpp"
#include "test_support.hpp"

namespace {

using namespace globe_test;

struct Shaded {
  fs::path dir;
  std::string global, himalaya, himalaya_analysis;
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
           tiler() + " terrain -q " + at("himalaya.tif") + " -o " + at("himalaya.mbtiles"),
           tiler() + " analyze -q " + at("himalaya.mbtiles") + " --layers skyview -o " +
               at("himalaya_analysis.mbtiles")},
          dir);
    });
    k.global = (k.dir / "etopo.mbtiles").string();
    k.himalaya = (k.dir / "himalaya.mbtiles").string();
    k.himalaya_analysis = (k.dir / "himalaya_analysis.mbtiles").string();
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

// A tilted plane is lit the same everywhere: no row or column of its
// hillshade stands out, also where the blocks meet (normals there come from
// the neighbour's samples; before, a one-sided difference drew a faint line
// on every block edge). The plane lies in the tiling's CRS (web mercator), so
// its slope is the same in every block.
TEST(ViewerShading, APlaneIsLitEvenlyAcrossBlockEdges) {
  TempDir dir;
  const double gt[6] = {1000000, 20, 0, 5000000, 0, -20};
  write_dem((dir / "plane.tif").string(), 600, 600, gt, "EPSG:3857", GDT_Float32,
            [](int x, int y) { return 1000.0 + 0.3 * 20 * x + 0.2 * 20 * y; });
  const std::string pkg = (dir / "plane.mbtiles").string(), png = (dir / "plane.png").string();
  ASSERT_TRUE(run_all({tiler() + " terrain -q " + (dir / "plane.tif").string() + " -o " + pkg},
                      dir.path()));
  // Straight down, east of the middle (9.045 E, 40.87 N), the plane filling the frame, at a
  // height where the finest zoom is drawn: several block edges cross it.
  const RunResult r = view(pkg + " --size 480x270 --camera=9.045,40.87,8000,0,0 --snapshot " + png +
                               " --stats --frames 1",
                           dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int w = 0, h = 0;
  const std::vector<uint8_t> rgb = read_rgb(png, w, h);
  ASSERT_EQ(size_t(w) * h * 3, rgb.size());
  // Every terrain pixel's grey against the frame's median grey (the sky, in a
  // corner where the plane is lowest, is left out).
  auto sky = [&](int x, int y) {
    const uint8_t* p = &rgb[(size_t(std::clamp(y, 0, h - 1)) * w + std::clamp(x, 0, w - 1)) * 3];
    return p[2] > p[0] + 20;
  };
  std::vector<int> grey;  // -1: sky, or the data's own edge next to it (4 px)
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      bool near_sky = false;
      for (int dy = -4; dy <= 4; ++dy)
        for (int dx = -4; dx <= 4; ++dx)
          near_sky = near_sky || sky(x + dx, y + dy);
      grey.push_back(near_sky ? -1 : rgb[(size_t(y) * w + x) * 3]);
    }
  std::vector<int> sorted;
  for (int g : grey)
    if (g >= 0) sorted.push_back(g);
  ASSERT_GT(sorted.size(), grey.size() * 9 / 10);
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const int median = sorted[sorted.size() / 2];
  // A seam is a line of pixels lit differently: none may stand out by more
  // than 2 grey levels (rounding).
  size_t off = 0;
  for (int g : grey)
    off += g >= 0 && std::abs(g - median) > 2;
  EXPECT_EQ(off, 0u) << "pixels lit unlike the plane (grey " << median << ")";
}

// The standard deviation of a frame's grey (R+G+B)/3.
double grey_std(const std::string& png) {
  int w = 0, h = 0;
  const std::vector<uint8_t> rgb = read_rgb(png, w, h);
  double sum = 0, sum2 = 0;
  const size_t n = size_t(w) * h;
  for (size_t i = 0; i < n; ++i) {
    const double g = (rgb[3 * i] + rgb[3 * i + 1] + rgb[3 * i + 2]) / 3.0;
    sum += g;
    sum2 += g * g;
  }
  return n ? std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n))) : 0;
}

// Readable by default: mountains on a coarse global grid (etopo20, 37 km
// samples, about nine across the frame) are shaded with contrast, not a grey
// sheet (the relief stretch, app/relief_scale); --exaggeration given is the
// user's own relief and turns the stretch off.
TEST(ViewerShading, MountainsOnACoarseGridAreReadableByDefault) {
  TempDir dir;
  const std::pair<const char*, const char*> views[] = {{"himalaya", "86.9,27.9,400000,0,0"},
                                                       {"alps", "10,46.3,300000,0,0"},
                                                       {"andes", "-70,-32.65,400000,0,0"}};
  for (const auto& [name, camera] : views) {
    const std::string png = (dir / (std::string(name) + ".png")).string();
    const std::string base = packages().global + " --size 320x180 --camera=" + camera;
    ASSERT_EQ(view(base + " --snapshot " + png, dir.path()).exit_code, 0) << name;
    const double stretched = grey_std(png);
    ASSERT_EQ(view(base + " --exaggeration 1 --snapshot " + png, dir.path()).exit_code, 0);
    const double plain = grey_std(png);
    std::printf("%s: grey std %.1f by default, %.1f with --exaggeration 1\n", name, stretched,
                plain);
    EXPECT_GE(stretched, 8) << name;
    EXPECT_LT(plain, stretched / 2) << name << ": --exaggeration turns the stretch off";
  }
}

// Readable by default, the analysis modes: on the coarse grid the built-in
// slope ramp (0..45 degrees) and sky-view ramp (0.65..1) would stay pale or
// white; stretched to the data's own 95th-percentile slope and 5th-percentile
// sky-view factor (app/data_ranges), they span most of their ramp. (The
// fine jacksboro package keeps the fixed ramps: its expected pictures in
// viewer_analysis_test and viewer_cli_test are unchanged.)
TEST(ViewerShading, AnalysisModesSpanTheirRampOnACoarseGrid) {
  TempDir dir;
  const std::string base = packages().himalaya + " " + packages().himalaya_analysis +
                           " --size 320x180 --camera=86.9,27.9,400000,0,0 --stats --snapshot ";
  // Per mode: the position along the built-in ramp of a pixel (0 its start).
  const std::pair<const char*, double (*)(const uint8_t*)> modes[] = {
      {"slope", [](const uint8_t* p) { return (255.0 - p[1]) / 229.5; }},  // cream -> red
      {"skyview", [](const uint8_t* p) { return 1.0 - p[0] / 255.0; }}};   // white -> black
  for (const auto& [mode, along] : modes) {
    const std::string png = (dir / (std::string(mode) + ".png")).string();
    const RunResult r = view(base + png + " --shading " + mode, dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    int w = 0, h = 0;
    const std::vector<uint8_t> rgb = read_rgb(png, w, h);
    std::vector<double> t;
    for (size_t i = 0; i < size_t(w) * h; ++i)
      t.push_back(along(&rgb[3 * i]));
    std::sort(t.begin(), t.end());
    const double p50 = t[t.size() / 2], p99 = t[t.size() * 99 / 100];
    std::printf("%s: ramp position p50 %.2f, p99 %.2f; grey std %.1f\n", mode, p50, p99,
                grey_std(png));
    EXPECT_GE(p99, 0.8) << mode << ": the steepest/most enclosed ground reaches the ramp's end";
    EXPECT_GE(p50, 0.1) << mode;
    EXPECT_GE(grey_std(png), 8) << mode;
  }
  // The stretch is reported, and stays within the fixed ramps.
  const RunResult r = view(base + (dir / "s.png").string() + " --shading slope", dir.path());
  EXPECT_NE(r.out.find("\"slope_ramp_top_deg\": "), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("\"slope_ramp_top_deg\": 45.00"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("\"skyview_ramp_low\": 0.6500"), std::string::npos) << r.out;
}

// The magic lens: outside its circle the frame is the frame without it, byte
// for byte; inside, the frame drawn entirely in the lens's mode (a pixel's
// width around the rim left out: the circle cuts those pixels).
TEST(ViewerShading, TheLensShowsItsModeInsideAndChangesNothingOutside) {
  TempDir dir;
  const std::string base = packages().himalaya + " --size 320x180 --camera=86.9,27.9,400000,30,45";
  auto shot = [&](const std::string& name, const std::string& options) {
    const std::string png = (dir / (name + ".png")).string();
    EXPECT_EQ(view(base + " " + options + " --snapshot " + png, dir.path()).exit_code, 0) << name;
    int w = 0, h = 0;
    return read_rgb(png, w, h);
  };
  const std::vector<uint8_t> plain = shot("plain", ""), slope = shot("slope", "--shading slope"),
                             lens = shot("lens", "--lens 150,100,60:slope");
  EXPECT_GT(expect_lens_frame(plain, slope, lens, 320, 180, 150, 100, 60), 10000u);
  // Isolines only inside the lens.
  const std::vector<uint8_t> iso = shot("iso", "--isolines 500"),
                             iso_lens = shot("iso_lens", "--lens 150,100,60:isolines=500");
  EXPECT_GT(expect_lens_frame(plain, iso, iso_lens, 320, 180, 150, 100, 60), 10000u);
  // A lens mode that needs an analysis package is refused without one.
  EXPECT_EQ(
      view(base + " --lens 10,10,5:skyview --snapshot " + (dir / "x.png").string(), dir.path())
          .exit_code,
      2);
}

// The lens in the window: K turns it on where the pointer is (radius 120 px,
// elevation inside the hillshade), it follows the pointer, and the wheel with
// Shift held resizes it (x 1.15 a notch); each frame equals the headless
// --lens frame of that circle.
TEST(ViewerShadingWindow, TheLensFollowsThePointerAndShiftWheelResizesIt) {
  TempDir dir;
  const std::string base = packages().himalaya + " --size 320x180 --camera=86.9,27.9,400000,30,45";
  const RunResult w = run(
      "xvfb-run -a -s '-screen 0 640x480x24' " + globe_test::paths::test_data_dir() +
          "/window/drive_keys.sh " + dir.path().string() +
          " '@move:100,90 k @move:150,100;@shiftwheel:down @shiftwheel:down @shiftwheel:down' " +
          viewer() + " --platform glfw " + base,
      dir.path());
  ASSERT_EQ(w.exit_code, 0) << w.err << read_file(dir / "viewer.stderr");
  const std::pair<const char*, double> expect[] = {{"globe-view-1.png", 120},
                                                   {"globe-view-2.png", 120 / std::pow(1.15, 3)}};
  std::vector<std::vector<uint8_t>> headless;
  for (const auto& [shot, radius] : expect) {
    const std::string snap = (dir / (std::string("headless-") + shot)).string();
    ASSERT_EQ(
        view(base + " --lens 150,100," + std::to_string(radius) + " --snapshot " + snap, dir.path())
            .exit_code,
        0);
    int w1 = 0, h1 = 0, w2 = 0, h2 = 0;
    const auto got = read_rgb((dir / shot).string(), w1, h1), want = read_rgb(snap, w2, h2);
    ASSERT_EQ(got.size(), want.size()) << shot;
    std::printf("%s: PSNR %.1f dB to the headless lens of radius %.1f\n", shot, psnr(got, want),
                radius);
    EXPECT_GT(psnr(got, want), 35.0) << shot;
    headless.push_back(want);
  }
  EXPECT_LT(psnr(headless[0], headless[1]), 30.0) << "the two lenses differ";
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
