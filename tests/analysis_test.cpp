// globe-tiler analyze as a user runs it: slope and aspect against the
// gdaldem program on the terrain's own finest zoom (extracted), slopes of
// geodetic ramps against textbook WGS84 radii written here, seamless block
// edges, identical bytes for any thread count, and clear errors.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "raster_fixtures.hpp"
#include "test_support.hpp"

namespace {

using namespace globe_test;

struct Comparison {
  size_t compared = 0, peer_only = 0, ours_only = 0;
  double worst = 0;
};

// |ours - peer| over pixels where both have values; angles compared modulo
// 360. The raster's outer ring is left out: there gdaldem -compute_edges
// extrapolates past the raster's border, a border that is only the extract's
// (ours has the neighbouring tiles, or no data there, where it substitutes
// the centre as gdaldem does next to nodata).
// `slope`, when given, limits the comparison to samples steeper than 0.5
// degrees: below, the aspect of a gradient of a few height quanta depends on
// rounding (gdaldem computes in single precision).
Comparison compare(const Raster& ours, const Raster& peer, bool angle,
                   const Raster* slope = nullptr) {
  Comparison c;
  EXPECT_EQ(ours.width, peer.width);
  EXPECT_EQ(ours.height, peer.height);
  if (ours.data.size() != peer.data.size()) return c;
  for (size_t i = 0; i < ours.data.size(); ++i) {
    const size_t x = i % ours.width, y = i / ours.width;
    if (x == 0 || y == 0 || x + 1 == size_t(ours.width) || y + 1 == size_t(ours.height)) continue;
    if (slope && !(slope->data[i] >= 0.5)) continue;
    const double a = ours.data[i], b = peer.data[i] == -9999 ? NAN : peer.data[i];
    if (std::isnan(b)) {
      if (!std::isnan(a)) ++c.ours_only;
      continue;
    }
    if (std::isnan(a)) {
      ++c.peer_only;
      continue;
    }
    double d = std::abs(a - b);
    if (angle) d = std::min(d, 360 - d);
    c.worst = std::max(c.worst, d);
    ++c.compared;
  }
  return c;
}

struct Sample {
  const char* file;
  int max_zoom;  // of its local terrain package
};

void PrintTo(const Sample& s, std::ostream* os) {
  *os << s.file;
}

class AnalyzeVsGdaldem : public ::testing::TestWithParam<Sample> {};

TEST_P(AnalyzeVsGdaldem, SlopeAndAspectWithinATenthOfADegree) {
  TempDir dir;
  const std::string pkg = (dir / "t.mbtiles").string(), ana = (dir / "a.mbtiles").string();
  ASSERT_EQ(
      run(tiler() + " terrain -q --tiling local " + sample(GetParam().file).string() + " -o " + pkg,
          dir.path())
          .exit_code,
      0);
  const RunResult a = run(tiler() + " analyze -q " + pkg + " -o " + ana, dir.path());
  ASSERT_EQ(a.exit_code, 0) << a.err;
  // Every zoom: each is analysed from its own heights. Brasilia's zoom 1 is
  // 2 x 2 blocks: their shared edges lie inside the extract, where gdaldem
  // sees no seam, so this also checks that block edges are seamless.
  for (int z = 0; z <= GetParam().max_zoom; ++z) {
    const std::string zs = std::to_string(z), dem = (dir / ("z" + zs + ".tif")).string();
    ASSERT_EQ(
        run(tiler() + " extract " + pkg + " --zoom " + zs + " -o " + dem, dir.path()).exit_code, 0);
    for (const std::string layer : {"slope", "aspect"}) {
      const std::string peer = (dir / (layer + zs + ".gdaldem.tif")).string(),
                        ours = (dir / (layer + zs + ".tif")).string();
      const RunResult g =
          run("gdaldem " + layer + " -q -compute_edges " + dem + " " + peer, dir.path());
      ASSERT_EQ(g.exit_code, 0) << g.err;
      const RunResult e =
          run(tiler() + " extract " + ana + " --zoom " + zs + " --layer " + layer + " -o " + ours,
              dir.path());
      ASSERT_EQ(e.exit_code, 0) << e.err;
      const Raster slope = read_raster((dir / ("slope" + zs + ".tif")).string());
      const Comparison c = compare(read_raster(ours), read_raster(peer), layer == "aspect",
                                   layer == "aspect" ? &slope : nullptr);
      std::printf(
          "%s zoom %d %s: %zu samples compared, worst %.4f deg, peer only %zu, ours only "
          "%zu\n",
          GetParam().file, z, layer.c_str(), c.compared, c.worst, c.peer_only, c.ours_only);
      EXPECT_GT(c.compared, 5000u);
      EXPECT_LE(c.worst, 0.1) << layer << " zoom " << z;
      EXPECT_EQ(c.peer_only, 0u) << layer << " zoom " << z;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Samples, AnalyzeVsGdaldem,
                         ::testing::Values(Sample{"brasilia.tif", 1}, Sample{"olinda.tif", 0}),
                         [](const auto& info) {
                           std::string n = info.param.file;
                           return n.substr(0, n.find('.'));
                         });

// Planar ramps in longitude/latitude on the geodetic tiling: the slope
// follows from the WGS84 radii of curvature (textbook formulas, here).
TEST(AnalyzeGeodetic, RampSlopesFollowTheEllipsoid) {
  TempDir dir;
  const double a = 6378137.0, e2 = 6.69437999014e-3, deg = std::numbers::pi / 180;
  const double gt[6] = {10, 0.01, 0, 61, 0, -0.01};  // 10..12 E, 59..61 N, 0.01 deg pixels
  const std::string north = (dir / "n.tif").string(), east = (dir / "e.tif").string();
  write_dem(north, 200, 200, gt, "EPSG:4326", GDT_Float32,
            [](int, int y) { return 2000 - 5.0 * y; });
  write_dem(east, 200, 200, gt, "EPSG:4326", GDT_Float32,
            [](int x, int) { return 1000 + 5.0 * x; });
  for (const auto& [src, dir_name] : {std::pair{north, "north"}, std::pair{east, "east"}}) {
    const std::string pkg = (dir / (std::string(dir_name) + ".mbtiles")).string(),
                      ana = (dir / (std::string(dir_name) + "_a.mbtiles")).string(),
                      out = (dir / (std::string(dir_name) + "_slope.tif")).string();
    ASSERT_EQ(run(tiler() + " terrain -q --tiling geodetic --max-zoom 8 " + src + " -o " + pkg,
                  dir.path())
                  .exit_code,
              0);
    ASSERT_EQ(run(tiler() + " analyze -q " + pkg + " -o " + ana, dir.path()).exit_code, 0);
    const RunResult e =
        run(tiler() + " extract " + ana + " --zoom 8 --layer slope -o " + out, dir.path());
    ASSERT_EQ(e.exit_code, 0) << e.err;
    const Raster r = read_raster(out);
    size_t checked = 0;
    double worst = 0;
    // Interior samples (two samples from the data's edges): the ramp rises 5 m
    // per 0.01 degree of source pixel.
    for (int y = 0; y < r.height; ++y)
      for (int x = 0; x < r.width; ++x) {
        const double lon = r.gt[0] + (x + 0.5) * r.gt[1], lat = r.gt[3] + (y + 0.5) * r.gt[5];
        const double sp = r.gt[1];
        if (lon < 10 + 3 * sp || lon > 12 - 3 * sp || lat < 59 + 3 * sp || lat > 61 - 3 * sp)
          continue;
        if (std::isnan(r.at(x, y))) continue;
        const double s2 = std::sin(lat * deg) * std::sin(lat * deg);
        const double m = a * (1 - e2) / std::pow(1 - e2 * s2, 1.5);
        const double n = a / std::sqrt(1 - e2 * s2);
        const double metres_per_deg =
            dir_name == std::string("north") ? m * deg : n * std::cos(lat * deg) * deg;
        const double want = std::atan(5.0 / 0.01 / metres_per_deg) / deg;
        worst = std::max(worst, std::abs(r.at(x, y) - want));
        ++checked;
      }
    std::printf("%s ramp: %zu samples, worst slope error %.4f deg\n", dir_name, checked, worst);
    EXPECT_GT(checked, 1000u);
    // Bilinear resampling keeps the ramp linear; heights are quantized to
    // the package's height step.
    EXPECT_LT(worst, 0.05) << dir_name;
  }
}

TEST(Analyze, ThreadCountsGiveIdenticalBytes) {
  TempDir dir;
  const std::string pkg = (dir / "t.mbtiles").string();
  ASSERT_EQ(
      run(tiler() + " terrain -q --tiling local " + sample("brasilia.tif").string() + " -o " + pkg,
          dir.path())
          .exit_code,
      0);
  // The same output path (it is in the recorded command line), one after the other.
  std::string bytes[2];
  for (int j = 1; j <= 2; ++j) {
    const RunResult r =
        run(tiler() + " analyze -q --force -j " + std::to_string(j) + " --layers slope,curvature " +
                pkg + " -o " + (dir / "a.mbtiles").string(),
            dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    bytes[j - 1] = read_file(dir / "a.mbtiles");
  }
  EXPECT_TRUE(bytes[0] == bytes[1]) << "-j 1 and -j 2 differ";
  const RunResult v = run(tiler() + " validate " + (dir / "a.mbtiles").string(), dir.path());
  EXPECT_EQ(v.exit_code, 0) << v.out;
}

TEST(Analyze, BadInputIsAClearError) {
  TempDir dir;
  const std::string pkg = (dir / "t.mbtiles").string(), ana = (dir / "a.mbtiles").string();
  ASSERT_EQ(
      run(tiler() + " terrain -q --tiling local " + sample("olinda.tif").string() + " -o " + pkg,
          dir.path())
          .exit_code,
      0);
  RunResult r =
      run(tiler() + " analyze " + sample("olinda.tif").string() + " -o " + ana, dir.path());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("olinda.tif"), std::string::npos) << r.err;
  r = run(tiler() + " analyze " + pkg + " --layers slope,wetness -o " + ana, dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown layer 'wetness'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(ana));
  ASSERT_EQ(run(tiler() + " analyze -q " + pkg + " -o " + ana, dir.path()).exit_code, 0);
  r = run(tiler() + " analyze " + ana + " -o " + (dir / "b.mbtiles").string(), dir.path());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("not a terrain package"), std::string::npos) << r.err;
  r = run(tiler() + " extract " + ana + " --zoom 0 -o " + (dir / "x.tif").string(), dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--layer is required"), std::string::npos) << r.err;
  r = run(tiler() + " extract " + ana + " --zoom 0 --layer plan_curvature -o " +
              (dir / "x.tif").string(),
          dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("holds slope (degrees), aspect (degrees)"), std::string::npos) << r.err;
  r = run(tiler() + " info " + ana, dir.path());
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("analysis: slope (degrees), aspect (degrees)"), std::string::npos) << r.out;
}

}  // namespace
