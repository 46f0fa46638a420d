// globe-tiler analyze --layers skyview as a user runs it, against a horizon
// scan written here: every half sample out to the full radius, in every
// direction, on the terrain's own finest zoom (extracted). Small blocks
// (65 samples) put the radius past the two-block halo, so the far field
// must come from the coarser zooms (docs/analysis.md "Sky view").
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "raster_fixtures.hpp"
#include "test_support.hpp"

namespace {

using namespace globe_test;

// The sky-view factor by brute force: 1 - mean over `directions` azimuths
// (clockwise from north) of sin(horizon elevation), the horizon being the
// highest angle over every half sample along the ray out to the radius,
// heights bilinear in the grid; the ray ends at the grid's edge or no data.
// Square cells in metres (a projected grid).
double brute_force_sky_view(const Raster& dem, int x, int y, double radius_m, int directions) {
  const double sp = dem.gt[1], h0 = dem.at(x, y);
  double sum = 0;
  for (int k = 0; k < directions; ++k) {
    const double az = 2 * std::numbers::pi * k / directions;
    // cos(pi / 2) is 6e-17, not 0: a ray along a row on the grid's edge
    // would step off the grid at once.
    const auto exact = [](double v) { return std::abs(v) < 1e-12 ? 0.0 : v; };
    const double east = exact(std::sin(az)), north = exact(std::cos(az));
    double best = 0;
    for (double d = sp / 2; d <= radius_m + 1e-6; d += sp / 2) {
      const double fx = x + east * d / sp, fy = y - north * d / sp;
      const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
      if (x0 < 0 || y0 < 0 || x0 + 1 >= dem.width || y0 + 1 >= dem.height) break;
      const double a = dem.at(x0, y0), b = dem.at(x0 + 1, y0), c = dem.at(x0, y0 + 1),
                   e = dem.at(x0 + 1, y0 + 1);
      if (std::isnan(a) || std::isnan(b) || std::isnan(c) || std::isnan(e)) break;
      const double tx = fx - x0, ty = fy - y0;
      const double h = (a * (1 - tx) + b * tx) * (1 - ty) + (c * (1 - tx) + e * tx) * ty;
      best = std::max(best, std::atan((h - h0) / d));
    }
    sum += std::sin(best);
  }
  return 1 - sum / directions;
}

// Whether a sample lies within 3 samples of no data (the warped DEM's
// corners): there a ray ends within a few samples, and whether its last
// steps, where the horizon is steepest, fall half a sample before the edge
// or on it decides much; the two scans step differently (every half sample
// here, every sample near the start there). Elsewhere the end of a ray at no
// data decides little.
bool near_no_data(const Raster& dem, int x, int y) {
  for (int j = -3; j <= 3; ++j)
    for (int i = -3; i <= 3; ++i) {
      const int u = x + i, v = y + j;
      if (u >= 0 && v >= 0 && u < dem.width && v < dem.height && std::isnan(dem.at(u, v)))
        return true;
    }
  return false;
}

struct SkyCase {
  const char* name;
  // How the test's DEM is made from the sample: "" to use it as it is, else
  // gdalwarp options (the sample is geographic: warped to metres).
  const char* sample;
  const char* warp;
  int block;  // samples per block side: its halo is two blocks
  double radius_m;
  int directions;
  int stride;      // every stride-th sample of each row and column is checked
  double min_far;  // how much the horizon past the halo must change somewhere
};

void PrintTo(const SkyCase& c, std::ostream* os) {
  *os << c.name;
}

// Jacksboro (geographic, 3") warped to UTM at 60 m, its corners without
// data; and its middle 16 km at 30 m.
constexpr const char* kJacksboroUtm = "-t_srs EPSG:32617 -tr 60 60 -r bilinear -dstnodata -9999";
constexpr const char* kJacksboroUtm30 =
    "-t_srs EPSG:32617 -tr 30 30 -te 201600 4046300 217600 4062300 -r bilinear -dstnodata -9999";

class AnalyzeSkyview : public ::testing::TestWithParam<SkyCase> {};

TEST_P(AnalyzeSkyview, MatchesABruteForceHorizonScanAtTheFullRadius) {
  const SkyCase& c = GetParam();
  TempDir dir;
  std::string input = sample(c.sample).string();
  if (*c.warp) {
    const std::string warped = (dir / "warped.tif").string();
    const RunResult w =
        run("gdalwarp -q " + std::string(c.warp) + " " + input + " " + warped, dir.path());
    ASSERT_EQ(w.exit_code, 0) << w.err;
    input = warped;
  }
  const std::string pkg = (dir / "t.mbtiles").string(), ana = (dir / "a.mbtiles").string();
  ASSERT_TRUE(build_terrain("--tiling local --block-size " + std::to_string(c.block), input, pkg,
                            dir.path()));
  const RunResult a = run(tiler() + " analyze -q --layers skyview --skyview-radius " +
                              std::to_string(int(c.radius_m)) + " --skyview-directions " +
                              std::to_string(c.directions) + " " + pkg + " -o " + ana,
                          dir.path());
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const RunResult info = run(tiler() + " info " + ana, dir.path());
  EXPECT_NE(info.out.find("reached at every zoom"), std::string::npos) << info.out;
  const std::string z = std::to_string(integer_after(info.out, "maxzoom"));
  const std::string dem = (dir / "dem.tif").string(), sky = (dir / "sky.tif").string();
  ASSERT_EQ(run(tiler() + " extract " + pkg + " --zoom " + z + " -o " + dem, dir.path()).exit_code,
            0);
  const RunResult e =
      run(tiler() + " extract " + ana + " --zoom " + z + " --layer skyview -o " + sky, dir.path());
  ASSERT_EQ(e.exit_code, 0) << e.err;
  const Raster h = read_raster(dem), ours = read_raster(sky);
  ASSERT_EQ(h.width, ours.width);
  ASSERT_EQ(h.height, ours.height);
  // The radius must lie past the halo of two blocks, or the test would not
  // reach the coarser zooms.
  const double halo_m = 2 * (c.block - 1) * h.gt[1];
  ASSERT_GT(c.radius_m, halo_m) << "zoom " << z << " spacing " << h.gt[1];
  size_t compared = 0, ours_missing = 0, edge = 0;
  double sum = 0, worst = 0, lowest = 1, far = 0;
  for (int y = 0; y < h.height; y += c.stride)
    for (int x = 0; x < h.width; x += c.stride) {
      if (std::isnan(h.at(x, y))) continue;
      if (near_no_data(h, x, y)) {
        ++edge;
        continue;
      }
      if (std::isnan(ours.at(x, y))) {
        ++ours_missing;
        continue;
      }
      const double want = brute_force_sky_view(h, x, y, c.radius_m, c.directions);
      // What the far field adds: the same scan stopped at the halo.
      far = std::max(far, brute_force_sky_view(h, x, y, halo_m, c.directions) - want);
      const double d = std::abs(ours.at(x, y) - want);
      sum += d;
      worst = std::max(worst, d);
      lowest = std::min(lowest, want);
      ++compared;
    }
  const double mean = compared ? sum / compared : 1;
  std::printf(
      "%s: %zu samples (zoom %s, %.0f m), mean |ours - brute force| %.4f, worst %.4f; "
      "lowest %.3f; the far field changes up to %.3f; %zu next to no data not compared\n",
      c.name, compared, z.c_str(), h.gt[1], mean, worst, lowest, far, edge);
  EXPECT_GT(compared, 5000u);
  EXPECT_EQ(ours_missing, 0u);
  EXPECT_LE(worst, 0.02);
  EXPECT_LT(lowest, 0.95) << "the sample has valleys: some sky must be hidden";
  EXPECT_GE(far, c.min_far) << "past the halo the horizon must matter, or the case proves little";
}

INSTANTIATE_TEST_SUITE_P(
    Samples, AnalyzeSkyview,
    ::testing::Values(SkyCase{"brasilia_3km_16", "brasilia.tif", "", 33, 3000, 16, 3, 0.002},
                      SkyCase{"brasilia_10km_16", "brasilia.tif", "", 33, 10000, 16, 4, 0.005},
                      SkyCase{"jacksboro_utm30_10km_16", "jacksboro.tif", kJacksboroUtm30, 33,
                              10000, 16, 6, 0.02},
                      SkyCase{"jacksboro_utm_15km_32", "jacksboro.tif", kJacksboroUtm, 33, 15000,
                              32, 7, 0.02}),
    [](const auto& info) { return std::string(info.param.name); });

// Where the zooms above run out (a terrain from --min-zoom 2), the rays end
// at the coarsest level's halo, and info says what radius each zoom reaches:
// zoom 2 (60 m samples) two of its 64-sample blocks less a step, 7,620 m;
// zoom 3 (30 m) as far, through zoom 2 (its own halo alone: 3,810 m).
TEST(AnalyzeSkyviewReach, InfoSaysWhatRadiusEachZoomReaches) {
  TempDir dir;
  const std::string pkg = (dir / "t.mbtiles").string(), ana = (dir / "a.mbtiles").string();
  ASSERT_TRUE(build_terrain("--tiling local --block-size 65 --min-zoom 2",
                            sample("brasilia.tif").string(), pkg, dir.path()));
  ASSERT_EQ(
      run(tiler() + " analyze -q --layers skyview --skyview-radius 10000 " + pkg + " -o " + ana,
          dir.path())
          .exit_code,
      0);
  const RunResult info = run(tiler() + " info --json " + ana, dir.path());
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("\"radius_by_zoom\":[{\"zoom\":2,\"radius_m\":7620},{\"zoom\":3,"
                          "\"radius_m\":7620}]"),
            std::string::npos)
      << info.out;
  const RunResult text = run(tiler() + " info " + ana, dir.path());
  EXPECT_NE(text.out.find("radius 10000 m; reached except at zoom 2 7620 m, zoom 3 7620 m"),
            std::string::npos)
      << text.out;
}

}  // namespace
