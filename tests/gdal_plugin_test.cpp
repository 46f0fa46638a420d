// The GDAL plugin driver as GDAL's own programs run it (GDAL_DRIVER_PATH set
// to the built plugin): gdal_translate turns a terrain package into the DEM
// it holds — equal, within the height step, to gdalwarp -et 0 of the source
// DEM onto the same grid (the independent reference) — in both global
// schemes; the other kinds are declined with the command that extracts them.
#include <gtest/gtest.h>

#include <string>

#include "line_fixtures.hpp"
#include "point_fixtures.hpp"
#include "raster_fixtures.hpp"
#include "test_paths.hpp"
#include "test_support.hpp"

namespace {

using namespace globe_test;

// Under ASan the plugin (instrumented) cannot load into GDAL's programs (not
// instrumented): the runtime must come first. These run in the plain build.
#ifdef GLOBE_ADDRESS_SANITIZER
#define SKIP_UNDER_ASAN() GTEST_SKIP() << "the ASan-built plugin does not load into gdalinfo"
#else
#define SKIP_UNDER_ASAN() (void)0
#endif

std::string with_plugin(const std::string& command) {
  return "GDAL_DRIVER_PATH=" + globe_test::paths::gdal_plugin_dir() + " " + command;
}

class GdalPlugin : public ::testing::TestWithParam<const char*> {};

TEST_P(GdalPlugin, GdalTranslateReadsTheTerrainAsItsDem) {
  SKIP_UNDER_ASAN();
  TempDir dir;
  const std::string src = sample("jacksboro.tif").string(), pkg = (dir / "t.mbtiles").string(),
                    out = (dir / "t.tif").string();
  ASSERT_TRUE(run_all({tiler() + " terrain -q --tiling " + GetParam() + " " + src + " -o " + pkg},
                      dir.path()));
  const RunResult info = run(with_plugin("gdalinfo " + pkg), dir.path());
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("Driver: GlobeTiles/"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("Type=Float32"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("Overviews: "), std::string::npos) << info.out;
  const RunResult t = run(with_plugin("gdal_translate -q " + pkg + " " + out), dir.path());
  ASSERT_EQ(t.exit_code, 0) << t.err;
  EXPECT_EQ(t.err, "");
  const Raster ours = read_raster(out);
  ASSERT_FALSE(ours.data.empty());
  const Raster ref = gdalwarp_reference({src}, ours, "bilinear", dir.path());
  ASSERT_EQ(ref.data.size(), ours.data.size());
  const HeightComparison c = compare_heights(ours, ref);
  // Integer DEM: height step 1 m, so within 0.5 m of the bilinear reference.
  EXPECT_GT(c.compared, ref.data.size() / 4);
  EXPECT_GT(c.compared, c.reference_valid * 99 / 100) << "heights missing where the DEM has them";
  EXPECT_LE(c.p999, 0.5 + 1e-6);
  EXPECT_LE(c.max_diff, 0.5 + 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Schemes, GdalPlugin, ::testing::Values("webmercator", "geodetic"));

TEST(GdalPluginKinds, OtherKindsAreDeclinedWithTheCommandThatExtractsThem) {
  SKIP_UNDER_ASAN();
  TempDir dir;
  write_text((dir / "l.geojson").string(),
             R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},)"
             R"("geometry":{"type":"LineString","coordinates":[[7,46],[8,47]]}}]})");
  write_places_csv((dir / "p.csv").string(), {"a"}, {{"x", 7.1, 46.1, {1}}, {"y", 8, 47, {2}}});
  const std::string lines = (dir / "l.mbtiles").string(), points = (dir / "p.mbtiles").string();
  ASSERT_TRUE(run_all({vectorize() + " lines -q " + (dir / "l.geojson").string() + " -o " + lines,
                       vectorize() + " points -q " + (dir / "p.csv").string() +
                           " --xy lon,lat --fields a -o " + points},
                      dir.path()));
  for (const std::string& pkg : {lines, points}) {
    const RunResult r =
        run(with_plugin("gdal_translate -q " + pkg + " " + (dir / "x.tif").string()), dir.path());
    EXPECT_NE(r.exit_code, 0) << pkg;
    EXPECT_NE(r.err.find("not a raster GDAL can read"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("globe-vectorize extract"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("Cannot parse tile data"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "x.tif"));
  }
}

}  // namespace
