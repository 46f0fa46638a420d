// globe-view drawing an analysis package (globe-tiler analyze) over its
// terrain, as a user runs it: sky view dark in the valleys of the Tennessee
// ridges, edges marking ridges and valleys, ambient occlusion darkening the
// elevation ramp there, slope and aspect from the package, and clear errors
// when a shading needs a layer the package lacks.
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

struct Packages {
  fs::path dir;
  std::string terrain, all, skyview_only, other;
};

const Packages& packages() {
  static const Packages s = [] {
    Packages k;
    k.dir = shared_folder("globe-view-analysis", [](const fs::path& dir) {
      auto at = [&](const char* name) { return (dir / name).string(); };
      return run_all(
          {tiler() + " terrain -q " + sample("jacksboro.tif").string() + " -o " + at("j.mbtiles"),
           tiler() + " analyze -q " + at("j.mbtiles") +
               " --layers slope,aspect,curvature,skyview,flow -o " + at("ja.mbtiles"),
           tiler() + " analyze -q " + at("j.mbtiles") + " --layers skyview -o " + at("js.mbtiles"),
           tiler() + " terrain -q --tiling local " + sample("brasilia.tif").string() + " -o " +
               at("b.mbtiles"),
           tiler() + " analyze -q " + at("b.mbtiles") + " -o " + at("ba.mbtiles")},
          dir);
    });
    k.terrain = (k.dir / "j.mbtiles").string();
    k.all = (k.dir / "ja.mbtiles").string();
    k.skyview_only = (k.dir / "js.mbtiles").string();
    k.other = (k.dir / "ba.mbtiles").string();
    return k;
  }();
  return s;
}

// 480 x 360: fine enough that the view draws the zooms whose samples
// resolve the valleys (about 60 m).
RunResult view(const std::string& args, const fs::path& dir) {
  return run(viewer() + " --platform osmesa --fit --size 480x360 " + args, dir);
}

int luminance(const uint8_t* p) {
  return (p[0] * 3 + p[1] * 6 + p[2]) / 10;
}

// The fraction of terrain pixels (not sky) that `pick` accepts.
template <class Pick>
double fraction(const std::vector<uint8_t>& rgb, Pick pick) {
  return Census().fraction(rgb, pick);
}

std::vector<uint8_t> snapshot(const std::string& args, const TempDir& dir,
                              const std::string& name) {
  const std::string snap = (dir / (name + ".png")).string();
  const RunResult r = view(args + " --snapshot " + snap, dir.path());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  int w = 0, h = 0;
  return read_rgb(snap, w, h);
}

TEST(ViewerAnalysis, SkyviewIsDarkInTheValleysAndWhiteOnOpenGround) {
  TempDir dir;
  const auto rgb =
      snapshot(packages().terrain + " " + packages().all + " --shading skyview", dir, "a");
  const double grey = fraction(
      rgb, [](const uint8_t* p) { return std::abs(p[0] - p[1]) < 3 && std::abs(p[1] - p[2]) < 3; });
  const double dark = fraction(rgb, [](const uint8_t* p) { return luminance(p) < 170; });
  const double open = fraction(rgb, [](const uint8_t* p) { return luminance(p) > 230; });
  std::printf("skyview: grey %.3f, dark %.3f, open %.3f\n", grey, dark, open);
  EXPECT_GT(grey, 0.99);
  EXPECT_GT(dark, 0.08) << "the hollows of the ridges";
  EXPECT_GT(open, 0.15) << "the valley floor and the plateau";
  expect_image((dir / "a.png").string(), "jacksboro_skyview");
}

TEST(ViewerAnalysis, EdgesMarkRidgesWarmAndValleysBlue) {
  TempDir dir;
  const auto rgb =
      snapshot(packages().terrain + " " + packages().all + " --shading edges", dir, "a");
  const double valley = fraction(rgb, [](const uint8_t* p) { return p[2] > p[0] + 60; });
  const double ridge = fraction(rgb, [](const uint8_t* p) { return p[0] > p[2] + 60; });
  std::printf("edges: valley %.3f, ridge %.3f\n", valley, ridge);
  EXPECT_GT(valley, 0.03);
  EXPECT_GT(ridge, 0.03);
  expect_image((dir / "a.png").string(), "jacksboro_edges");
}

// Rivers from the flow accumulation: light blue where they begin, deep blue
// downstream; the hillsides stay grey.
TEST(ViewerAnalysis, FlowDrawsTheRiversBlue) {
  TempDir dir;
  const auto rgb =
      snapshot(packages().terrain + " " + packages().all + " --shading flow", dir, "a");
  const double river = fraction(rgb, [](const uint8_t* p) { return p[2] > p[0] + 60; });
  const double deep = fraction(rgb, [](const uint8_t* p) { return p[2] > p[0] + 120; });
  const double grey = fraction(rgb, [](const uint8_t* p) { return std::abs(p[2] - p[0]) < 8; });
  std::printf("flow: river %.3f, deep %.3f, grey %.3f\n", river, deep, grey);
  EXPECT_GT(river, 0.01);
  EXPECT_LT(river, 0.3);
  EXPECT_GT(deep, 0.001);
  EXPECT_GT(grey, 0.6);
  expect_image((dir / "a.png").string(), "jacksboro_flow");
}

// --flow-animate / --flow-phase: pulses run downstream along the rivers. A
// V-shaped valley falling east carries one river along its middle row; a
// quarter cycle later its pulses lie a quarter of their spacing further
// east, and nothing but the river changed.
TEST(ViewerAnalysis, FlowPulsesMoveDownstream) {
  TempDir dir;
  const double gt[6] = {500000, 30, 0, 4000000, 0, -30};
  const std::string dem = (dir / "valley.tif").string(), t = (dir / "v.mbtiles").string(),
                    a = (dir / "va.mbtiles").string();
  write_dem(dem, 257, 257, gt, "EPSG:32632", GDT_Float32,
            [](int x, int y) { return 300 - 0.5 * x + 3.0 * std::abs(y - 128); });
  ASSERT_TRUE(build_terrain("--tiling local", dem, t, dir.path()));
  ASSERT_EQ(run(tiler() + " analyze -q --layers flow " + t + " -o " + a, dir.path()).exit_code, 0);
  const std::string base = t + " " + a + " --shading flow --flow-animate";
  const auto still = snapshot(t + " " + a + " --shading flow", dir, "still");
  const auto p0 = snapshot(base, dir, "p0");
  const auto p1 = snapshot(base + " --flow-phase 0.25", dir, "p1");
  ASSERT_EQ(p0.size(), size_t(480 * 360 * 3));
  ASSERT_EQ(p1.size(), p0.size());
  // The river: the row with the most blue pixels in the still image.
  auto blue = [](const uint8_t* p) { return p[2] > p[0] + 60; };
  int row = -1, most = 0;
  for (int y = 0; y < 360; ++y) {
    int n = 0;
    for (int x = 0; x < 480; ++x)
      n += blue(&still[(size_t(y) * 480 + x) * 3]);
    if (n > most) most = n, row = y;
  }
  ASSERT_GT(most, 100) << "no river drawn";
  // Away from the river (3 rows off, and more), the pulses change nothing.
  size_t changed_off_river = 0;
  for (int y = 0; y < 360; ++y)
    for (int x = 0; x < 480; ++x) {
      const size_t i = (size_t(y) * 480 + x) * 3;
      if (std::abs(y - row) > 3 && !blue(&still[i]) &&
          (p0[i] != p1[i] || p0[i + 1] != p1[i + 1] || p0[i + 2] != p1[i + 2]))
        ++changed_off_river;
    }
  EXPECT_EQ(changed_off_river, 0u);
  // Brightness along the river (the row and its neighbours), then the shift
  // of p1 against p0 that matches best.
  auto profile = [&](const std::vector<uint8_t>& rgb) {
    std::vector<double> v(480, 0);
    for (int y = row - 1; y <= row + 1; ++y)
      for (int x = 0; x < 480; ++x) {
        const uint8_t* q = &rgb[(size_t(y) * 480 + x) * 3];
        v[size_t(x)] += q[0] + q[1] + q[2];
      }
    return v;
  };
  const std::vector<double> a0 = profile(p0), a1 = profile(p1);
  std::vector<int> river_x;
  for (int x = 0; x < 480; ++x)
    if (blue(&still[(size_t(row) * 480 + x) * 3])) river_x.push_back(x);
  // The crests' spacing in pixels (it depends on the zoom drawn): from the
  // first to the last crest of p0 along the river.
  const double top = *std::max_element(a0.begin() + river_x.front(), a0.begin() + river_x.back());
  std::vector<int> crests;
  for (int x = river_x.front() + 1; x < river_x.back(); ++x)
    if (a0[size_t(x)] > 0.8 * top && a0[size_t(x)] >= a0[size_t(x - 1)] &&
        a0[size_t(x)] > a0[size_t(x + 1)] && (crests.empty() || x - crests.back() > 4))
      crests.push_back(x);
  ASSERT_GE(crests.size(), 3u) << "no pulses on the river";
  const double spacing = double(crests.back() - crests.front()) / double(crests.size() - 1);
  // The shift of p1 against p0 that matches best, within half a spacing.
  const int reach = int(spacing / 2);
  int best = 0;
  double best_error = 1e300, moved = 0;
  for (int shift = -reach; shift <= reach; ++shift) {
    double e = 0;
    for (int x : river_x)
      if (x + shift >= 0 && x + shift < 480)
        e += std::pow(a0[size_t(x)] - a1[size_t(x + shift)], 2);
    if (e < best_error) best_error = e, best = shift;
  }
  for (int x : river_x)
    moved += std::abs(a0[size_t(x)] - a1[size_t(x)]);
  std::printf(
      "flow pulses: river row %d (%d px), %zu crests %.1f px apart, shift %d px, mean "
      "change %.1f\n",
      row, most, crests.size(), spacing, best, moved / double(river_x.size()));
  EXPECT_GT(moved / double(river_x.size()), 20) << "the pulses did not change the river";
  // A quarter cycle: a quarter of the spacing, eastwards (downstream).
  EXPECT_NEAR(best, spacing / 4, 2.0);
  EXPECT_GT(best, 0) << "pulses must move east, downstream";
}

TEST(ViewerAnalysis, ColormapFilesColourSlopeAndFlow) {
  TempDir dir;
  const fs::path data = fs::path(globe_test::paths::test_data_dir()) / "render";
  const auto slope =
      snapshot(packages().terrain + " " + packages().all + " --shading slope --colormap " +
                   (data / "slope_colormap.txt").string(),
               dir, "slope");
  const double green = fraction(slope, [](const uint8_t* p) { return p[1] > p[0] + 40; });
  const double yellow =
      fraction(slope, [](const uint8_t* p) { return p[0] > 150 && p[1] > 130 && p[2] < 90; });
  const auto flow =
      snapshot(packages().terrain + " " + packages().all + " --shading flow --colormap " +
                   (data / "flow_colormap.txt").string(),
               dir, "flow");
  const double navy = fraction(flow, [](const uint8_t* p) { return p[2] > p[0] + 100; });
  // Pale blue (grey in the built-in flow shading): the file's first stop.
  const double pale = fraction(
      flow, [](const uint8_t* p) { return p[2] - p[0] > 10 && p[2] - p[0] < 60 && p[1] > p[0]; });
  std::printf("colormap: slope green %.3f, yellow %.3f; flow navy %.3f, pale %.3f\n", green, yellow,
              navy, pale);
  EXPECT_GT(green, 0.3);
  EXPECT_GT(yellow, 0.05);
  EXPECT_GT(navy, 0.01);
  EXPECT_GT(pale, 0.2);
  expect_image((dir / "slope.png").string(), "jacksboro_slope_colormap");
}

// --colormap colours aspect (degrees clockwise from north) and edges (the
// stretched curvature, -1 valleys .. 1 ridges) too. Both files here run red
// - white/blue - red: every colour on them (and their mixes with the grey of
// level ground, and shaded) has green no above min(red, blue), which the
// built-in hue wheel and orange ridges break.
TEST(ViewerAnalysis, ColormapFilesColourAspectAndEdges) {
  TempDir dir;
  const std::string aspect_file = (dir / "aspect.txt").string(),
                    edges_file = (dir / "edges.txt").string();
  std::ofstream(aspect_file) << "0 255 0 0\n180 0 0 255\n360 255 0 0\n";
  std::ofstream(edges_file) << "-1 0 0 255\n0 255 255 255\n1 255 0 0\n";
  auto on_ramp = [](const uint8_t* p) { return p[1] <= std::min(p[0], p[2]) + 4; };
  auto red = [](const uint8_t* p) { return p[0] > p[2] + 60; };
  auto blue = [](const uint8_t* p) { return p[2] > p[0] + 60; };
  const std::string base = packages().terrain + " " + packages().all;
  const auto builtin = snapshot(base + " --shading aspect", dir, "builtin");
  const auto aspect = snapshot(base + " --shading aspect --colormap " + aspect_file, dir, "aspect");
  const auto edges = snapshot(base + " --shading edges --colormap " + edges_file, dir, "edges");
  std::printf(
      "colormap: built-in aspect on the ramp %.3f; aspect on it %.3f (north red %.3f, "
      "south blue %.3f); edges on it %.3f (ridges red %.3f, valleys blue %.3f)\n",
      fraction(builtin, on_ramp), fraction(aspect, on_ramp), fraction(aspect, red),
      fraction(aspect, blue), fraction(edges, on_ramp), fraction(edges, red),
      fraction(edges, blue));
  EXPECT_LT(fraction(builtin, on_ramp), 0.9) << "the test cannot tell the ramp from the hues";
  EXPECT_GT(fraction(aspect, on_ramp), 0.99);
  EXPECT_GT(fraction(aspect, red), 0.08) << "slopes facing north";
  EXPECT_GT(fraction(aspect, blue), 0.08) << "slopes facing south";
  EXPECT_GT(fraction(edges, on_ramp), 0.99);
  EXPECT_GT(fraction(edges, red), 0.02) << "ridges";
  EXPECT_GT(fraction(edges, blue), 0.02) << "valleys";
}

TEST(ViewerAnalysis, AmbientOcclusionDarkensTheHollowsOnly) {
  TempDir dir;
  const std::string base = packages().terrain + " " + packages().all + " --shading elevation";
  const auto plain = snapshot(base, dir, "plain"),
             ao = snapshot(base + " --ambient-occlusion", dir, "ao");
  ASSERT_EQ(plain.size(), ao.size());
  size_t terrain = 0, darker = 0, same = 0;
  for (size_t i = 0; i + 2 < plain.size(); i += 3) {
    if (is_sky(&plain[i])) continue;
    ++terrain;
    const int d = luminance(&plain[i]) - luminance(&ao[i]);
    if (d > 30) ++darker;
    if (std::abs(d) * 10 <= luminance(&plain[i])) ++same;
  }
  std::printf("ambient occlusion: %zu terrain pixels, %zu much darker, %zu unchanged\n", terrain,
              darker, same);
  EXPECT_GT(darker, terrain / 50) << "the hollows";
  EXPECT_GT(same, terrain / 5) << "open ground keeps (within 10 %) its colour";
}

TEST(ViewerAnalysis, SlopeAndAspectComeFromThePackageWhenItHasThem) {
  TempDir dir;
  const std::string& t = packages().terrain;
  for (const std::string mode : {"slope", "aspect"}) {
    const auto own = snapshot(t + " --shading " + mode, dir, mode + "_own");
    const auto pkg = snapshot(t + " " + packages().all + " --shading " + mode, dir, mode + "_pkg");
    const auto sky =
        snapshot(t + " " + packages().skyview_only + " --shading " + mode, dir, mode + "_sky");
    ASSERT_EQ(own.size(), pkg.size());
    double sum = 0;
    for (size_t i = 0; i < own.size(); ++i)
      sum += std::abs(int(own[i]) - int(pkg[i]));
    const double mean = sum / double(own.size());
    std::printf("%s: mean |per-pixel - package| %.2f levels\n", mode.c_str(), mean);
    // Horn's 3 x 3 gradient of the package against the drawn triangles'
    // central differences: alike, not the same.
    EXPECT_GT(mean, 0.05) << mode << ": the package's layers were not drawn";
    EXPECT_LT(mean, 8.0) << mode;
    EXPECT_TRUE(sky == own) << mode << ": without the layers, the heights' own " << mode;
  }
}

// A broken analysis tile no longer takes its terrain block down (issue 55:
// the finest zoom of the analysis package made unreadable left the view
// without that zoom's terrain, and no picture): the terrain is drawn, the
// analysis from the parent's samples, each broken tile named with the
// analysis package.
TEST(ViewerAnalysis, BrokenAnalysisTilesAreDrawnFromTheirParent) {
  TempDir dir;
  const std::string pkg = (dir / "broken.mbtiles").string();
  fs::copy_file(packages().all, pkg);
  const RunResult s = run("sqlite3 " + pkg +
                              " \"UPDATE blobs SET tile_data = randomblob(100) WHERE blob_id IN "
                              "(SELECT blob_id FROM map WHERE zoom_level = (SELECT max(zoom_level) "
                              "FROM map));\"",
                          dir.path());
  ASSERT_EQ(s.exit_code, 0) << s.err;
  auto shot = [&](const std::string& name, const std::string& analysis, std::string* err) {
    const std::string png = (dir / (name + ".png")).string();
    const RunResult r = view(
        packages().terrain + " " + analysis + " --shading slope --snapshot " + png, dir.path());
    EXPECT_EQ(r.exit_code, 0) << name << "\n" << r.err;
    *err = r.err;
    int w = 0, h = 0;
    return read_rgb(png, w, h);
  };
  std::string intact_err, err;
  const auto intact = shot("intact", packages().all, &intact_err),
             broken = shot("broken", pkg, &err);
  EXPECT_NE(err.find("broken.mbtiles: tile "), std::string::npos) << err;
  EXPECT_NE(err.find("drawing its parent's samples there"), std::string::npos) << err;
  ASSERT_EQ(broken.size(), intact.size());
  EXPECT_GE(psnr(broken, intact), 30) << err;
}

TEST(ViewerAnalysis, MissingLayersAndOtherTilingsAreClearErrors) {
  TempDir dir;
  const std::string& t = packages().terrain;
  const std::string snap = " --snapshot " + (dir / "a.png").string();
  RunResult r = view(t + " --shading skyview" + snap, dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--shading skyview draws the skyview layer of an analysis package"),
            std::string::npos)
      << r.err;
  r = view(t + " " + packages().skyview_only + " --shading edges" + snap, dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("js.mbtiles has no plan_curvature layer"), std::string::npos) << r.err;
  r = view(t + " " + packages().skyview_only + " --shading flow" + snap, dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("js.mbtiles has no flow_accumulation layer; rebuild it with globe-tiler "
                       "analyze --layers ...,flow"),
            std::string::npos)
      << r.err;
  r = view(t + " " + packages().all + " --shading skyview --ambient-occlusion" + snap, dir.path());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  fs::remove(dir / "a.png");
  r = view(t + " " + packages().other + snap, dir.path());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("ba.mbtiles: its tiling"), std::string::npos) << r.err;
  r = view(t + " " + packages().all + " " + packages().skyview_only + snap, dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("two analysis packages"), std::string::npos) << r.err;
  r = view(packages().all + snap, dir.path());  // lines may go without terrain, analyses not
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("is an analysis of a terrain; give that terrain package too"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "a.png"));
}

}  // namespace
