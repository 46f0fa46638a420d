// Real DEMs from samples/ (fetched by samples/fetch.sh): tile, extract the
// finest zoom, and compare with the gdalwarp program (-et 0, same resampling)
// onto the same grid. Also: validate's invariants hold (shared edges, nested
// samples, saturated errors) and -j1 / -j2 packages are byte-identical.
#include <gtest/gtest.h>

#include <cmath>

#include "raster_fixtures.hpp"
#include "test_support.hpp"
#include "tileformat/mblock.hpp"
#include "tileformat/package.hpp"

using namespace globe_test;

namespace {

struct Case {
  std::string name, file, options;
  double step;          // the package's height step
  double min_coverage;  // fraction of reference samples that must be compared
};

// Allowed difference on top of step / 2 everywhere: reprojected coordinates
// are interpolated to within 1e-7 source pixels (kDefaultTransformTolerancePx),
// which moves a height by 1e-7 times the step between neighbouring source
// samples: < 1 mm below steps of 10 km. (Measured: the maximum is step / 2.)
constexpr double kTolerance = 0.001;

int max_zoom_of(const std::string& info) {
  const auto pos = info.find("maxzoom");
  return std::stoi(info.substr(info.find_first_of("0123456789", pos)));
}

class RealDem : public ::testing::TestWithParam<Case> {};

// Test names print the case name, not the struct's bytes.
[[maybe_unused]] void PrintTo(const Case& c, std::ostream* os) {
  *os << c.name;
}

}  // namespace

namespace {}  // namespace

TEST_P(RealDem, FinestZoomMatchesGdalwarp) {
  const Case& c = GetParam();
  TempDir dir;
  const auto src = sample(c.file);
  ASSERT_TRUE(fs::exists(src));
  const auto pkg = (dir / (c.name + ".mbtiles")).string();
  auto r =
      run(tiler() + " terrain -q " + c.options + " " + src.string() + " -o " + pkg, dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto v = run(tiler() + " validate " + pkg, dir.path());
  EXPECT_EQ(v.exit_code, 0) << v.out;
  auto info = run(tiler() + " info " + pkg, dir.path());
  const int z = max_zoom_of(info.out);
  const auto ours_path = (dir / "ours.tif").string();
  auto e = run(tiler() + " extract " + pkg + " --zoom " + std::to_string(z) + " -o " + ours_path,
               dir.path());
  ASSERT_EQ(e.exit_code, 0) << e.err;
  const Raster ours = read_raster(ours_path);
  const std::string resampling = c.options.find("near") != std::string::npos ? "near" : "bilinear";
  const Raster ref = gdalwarp_reference({src.string()}, ours, resampling, dir.path());
  ASSERT_EQ(ref.data.size(), ours.data.size());
  const HeightComparison cmp = compare_heights(ours, ref);
  std::printf(
      "%s: zoom %d, %zu samples compared, p99.9 |diff| %.4f m, max %.4f m (limit %.4f + %.4f), "
      "only ours %zu, only gdalwarp %zu\n",
      c.name.c_str(), z, cmp.compared, cmp.p999, cmp.max_diff, c.step / 2, kTolerance,
      cmp.only_ours, cmp.only_reference);
  EXPECT_LE(cmp.p999, c.step / 2 * (1 + 1e-6));
  EXPECT_LE(cmp.max_diff, c.step / 2 * (1 + 1e-6) + kTolerance);
  EXPECT_GE(static_cast<double>(cmp.compared),
            c.min_coverage * static_cast<double>(cmp.reference_valid));
}

INSTANTIATE_TEST_SUITE_P(
    Samples, RealDem,
    ::testing::Values(Case{"olinda", "olinda.tif", "", 0.01, 0.99},
                      Case{"jacksboro", "jacksboro.tif", "", 1.0, 0.99},
                      Case{"jacksboro_geodetic", "jacksboro.tif", "--tiling geodetic", 1.0, 0.99},
                      Case{"brasilia_local", "brasilia.tif", "--tiling local", 0.01, 0.999},
                      Case{"lux", "lux.tif", "", 1.0, 0.99},
                      Case{"etopo20_geodetic_near", "etopo20.tif",
                           "--tiling geodetic --resampling near", 0.01, 0.99},
                      Case{"etopo20_webmercator_near", "etopo20.tif", "--resampling near", 0.01,
                           0.99}),
    [](const auto& info) { return info.param.name; });

TEST(RealDemDeterminism, OneAndTwoThreadsGiveIdenticalBytes) {
  // Same options and output name (in two folders), only -j differs.
  TempDir dir;
  fs::create_directories(dir / "j1");
  fs::create_directories(dir / "j2");
  for (const std::string file : {"jacksboro.tif", "etopo20.tif"}) {
    const auto src = sample(file).string();
    for (const std::string j : {"j1", "j2"})
      ASSERT_EQ(run("cd " + (dir / j).string() + " && " + tiler() + " terrain -q -" + j +
                        " --force " + src + " -o out.mbtiles",
                    dir.path())
                    .exit_code,
                0);
    const bool same =
        read_file(dir / "j1" / "out.mbtiles") == read_file(dir / "j2" / "out.mbtiles");
    EXPECT_TRUE(same) << file << ": packages differ between -j1 and -j2";
  }
}

TEST(RealDemAntimeridian, GlobalDataCoversBothHemispheres) {
  // etopo20 spans longitudes 20..380: the part past 180 must appear west of
  // the antimeridian, so the geodetic package covers every root column.
  TempDir dir;
  const auto pkg = (dir / "e.mbtiles").string();
  ASSERT_EQ(run(tiler() + " terrain -q --tiling geodetic " + sample("etopo20.tif").string() +
                    " -o " + pkg,
                dir.path())
                .exit_code,
            0);
  auto info = run(tiler() + " info " + pkg, dir.path());
  EXPECT_NE(info.out.find("     0          2"), std::string::npos)
      << "zoom 0 should hold both roots:\n"
      << info.out;
  const auto west = (dir / "west.tif").string();
  ASSERT_EQ(
      run(tiler() + " extract " + pkg + " --zoom 1 --bbox -179,-10,-170,10 -o " + west, dir.path())
          .exit_code,
      0);
  const Raster r = read_raster(west);
  EXPECT_GT(r.valid_count(), r.data.size() / 2);
}

TEST(RealDemAntimeridian, WebMercatorTilesAtBothEdgesHoldData) {
  // Zoom 4 warps tiles in groups, including groups at x = 0 and x = 15 whose
  // windows touch the antimeridian: both edges must hold data, and validate's
  // invariants (edges, nesting, saturation) must hold.
  TempDir dir;
  const auto pkg = (dir / "w.mbtiles").string();
  ASSERT_EQ(
      run(tiler() + " terrain -q --max-zoom 4 " + sample("etopo20.tif").string() + " -o " + pkg,
          dir.path())
          .exit_code,
      0);
  EXPECT_EQ(run(tiler() + " validate " + pkg, dir.path()).exit_code, 0);
  for (const std::string bbox : {"-180,-5,-178,5", "178,-5,180,5"}) {
    const auto out = (dir / "edge.tif").string();
    ASSERT_EQ(run(tiler() + " extract --force " + pkg + " --zoom 4 --bbox " + bbox + " -o " + out,
                  dir.path())
                  .exit_code,
              0);
    const Raster r = read_raster(out);
    EXPECT_EQ(r.valid_count(), r.data.size())
        << bbox << ": samples without data at the antimeridian";
  }
}

TEST(RealDemCodec, RealBlocksRoundTripToIdenticalBytes) {
  // Every block of a real package decodes and re-encodes to the same bytes.
  TempDir dir;
  const auto pkg = (dir / "j.mbtiles").string();
  ASSERT_EQ(
      run(tiler() + " terrain -q " + sample("jacksboro.tif").string() + " -o " + pkg, dir.path())
          .exit_code,
      0);
  tileformat::PackageReader reader(pkg);
  size_t blocks = 0;
  reader.for_each_tile([&](tileformat::TileId id, std::span<const uint8_t> blob) {
    const auto block = tileformat::decode_mblock(blob);
    const auto again = tileformat::encode_mblock(block);
    EXPECT_TRUE(std::equal(blob.begin(), blob.end(), again.begin(), again.end())) << id.str();
    EXPECT_EQ(block.size, 257);
    ++blocks;
  });
  EXPECT_GT(blocks, 10u);
}

TEST(RealDemLocal, GlobalDataInItsOwnCrsKeepsEverySample) {
  // Local tiling of etopo20 (longitudes 20..380, its own CRS): the finest zoom
  // holds every source sample unchanged, across the 180 degree meridian.
  TempDir dir;
  const auto src = sample("etopo20.tif").string();
  const auto pkg = (dir / "l.mbtiles").string();
  ASSERT_EQ(run(tiler() + " terrain -q --tiling local " + src + " -o " + pkg, dir.path()).exit_code,
            0);
  auto info = run(tiler() + " info " + pkg, dir.path());
  const auto out = (dir / "l.tif").string();
  ASSERT_EQ(run(tiler() + " extract " + pkg + " --zoom " + std::to_string(max_zoom_of(info.out)) +
                    " -o " + out,
                dir.path())
                .exit_code,
            0);
  const Raster ours = read_raster(out), source = read_raster(src);
  size_t compared = 0;
  double worst = 0;
  for (int y = 0; y < source.height; ++y)
    for (int x = 0; x < source.width; ++x) {
      if (std::isnan(source.at(x, y))) continue;
      ASSERT_LT(x, ours.width);
      ASSERT_LT(y, ours.height);
      worst = std::max(worst, std::abs(ours.at(x, y) - source.at(x, y)));
      ++compared;
    }
  EXPECT_GT(compared, 500000u);
  EXPECT_LE(worst, 0.005 * (1 + 1e-6));
}
