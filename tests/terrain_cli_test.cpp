// globe-tiler terrain on bad input: a clear message naming the file, the
// documented exit code (docs/cli.md), and no output file left behind.
#include <gtest/gtest.h>

#include <algorithm>

#include "line_fixtures.hpp"
#include "raster_fixtures.hpp"
#include "test_support.hpp"

using namespace globe_test;

namespace {

const double kGeoGt[6] = {6.0, 0.01, 0, 50.0, 0, -0.01};  // 0.01 degree pixels near Luxembourg

std::string good_dem(const TempDir& dir, const std::string& srs = "EPSG:4326") {
  const auto path = (dir / "dem.tif").string();
  write_dem(path, 64, 48, kGeoGt, srs, GDT_Int16, [](int x, int y) { return 200 + x * 3 + y; });
  return path;
}

void expect_failure(const RunResult& r, int code, const std::string& message,
                    const fs::path& output) {
  EXPECT_EQ(r.exit_code, code) << r.err;
  EXPECT_NE(r.err.find(message), std::string::npos) << "stderr was: " << r.err;
  EXPECT_FALSE(fs::exists(output)) << "output left behind";
  EXPECT_FALSE(fs::exists(output.string() + ".tmp")) << "temporary output left behind";
  EXPECT_FALSE(fs::exists(output.string() + ".staging")) << "staging file left behind";
}

}  // namespace

TEST(TerrainCli, GoodInputBuildsAValidPackage) {
  TempDir dir;
  const auto dem = good_dem(dir);
  const auto out = dir / "out.mbtiles";
  auto r = run(tiler() + " terrain -q " + dem + " -o " + out.string(), dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << "-q must silence stderr: " << r.err;
  auto v = run(tiler() + " validate " + out.string(), dir.path());
  EXPECT_EQ(v.exit_code, 0) << v.out;
  auto info = run(tiler() + " info " + out.string(), dir.path());
  EXPECT_EQ(info.exit_code, 0);
  EXPECT_NE(info.out.find("application/vnd.globe.mblock"), std::string::npos);
}

// An output in a folder that does not exist (or is a file): every builder
// and export says which folder and what to do, exit 3 (output), not
// SQLite's "unable to open database file".
TEST(TerrainCli, OutputFolderMissingIsNamed) {
  TempDir dir;
  const auto dem = good_dem(dir);
  const std::string missing = (dir / "no" / "such").string();
  auto r = run(tiler() + " terrain -q " + dem + " -o " + missing + "/t.mbtiles", dir.path());
  expect_failure(r, 3, "the folder " + missing + " does not exist; create it",
                 dir / "no" / "such" / "t.mbtiles");
  r = run(tiler() + " imagery -q " + dem + " -o " + dem + "/i.mbtiles", dir.path());
  expect_failure(r, 3, dem + " is not a folder", dir / "i.mbtiles");
  ASSERT_EQ(run(tiler() + " terrain -q " + dem + " -o " + (dir / "t.mbtiles").string(), dir.path())
                .exit_code,
            0);
  r = run(tiler() + " export -q " + (dir / "t.mbtiles").string() + " --format terrarium -o " +
              missing + "/t.pmtiles",
          dir.path());
  expect_failure(r, 3, "the folder " + missing + " does not exist", dir / "no");
  write_text((dir / "l.geojson").string(),
             R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},)"
             R"("geometry":{"type":"LineString","coordinates":[[0,0],[1,1]]}}]})");
  r = run(
      vectorize() + " lines -q " + (dir / "l.geojson").string() + " -o " + missing + "/l.mbtiles",
      dir.path());
  expect_failure(r, 3, "the folder " + missing + " does not exist", dir / "no");
}

TEST(TerrainCli, MissingFile) {
  TempDir dir;
  auto r = run(
      tiler() + " terrain " + (dir / "nope.tif").string() + " -o " + (dir / "o.mbtiles").string(),
      dir.path());
  expect_failure(r, 1, "nope.tif: no such file", dir / "o.mbtiles");
}

TEST(TerrainCli, TextFile) {
  TempDir dir;
  std::ofstream(dir / "notes.tif") << "this is a text file, not a raster\n";
  auto r = run(
      tiler() + " terrain " + (dir / "notes.tif").string() + " -o " + (dir / "o.mbtiles").string(),
      dir.path());
  expect_failure(r, 1, "notes.tif: not a raster", dir / "o.mbtiles");
}

TEST(TerrainCli, TruncatedGeoTiff) {
  TempDir dir;
  const auto path = (dir / "big.tif").string();
  write_dem(path, 400, 400, kGeoGt, "EPSG:4326", GDT_Float32,
            [](int x, int y) { return x + y * 0.5; });
  fs::resize_file(path, fs::file_size(path) / 3);
  auto r = run(tiler() + " terrain " + path + " -o " + (dir / "o.mbtiles").string(), dir.path());
  expect_failure(r, 1, "big.tif", dir / "o.mbtiles");
  EXPECT_NE(r.err.find("truncated or corrupt"), std::string::npos) << r.err;
}

TEST(TerrainCli, NoCrsNeedsSourceSrs) {
  TempDir dir;
  const auto dem = good_dem(dir, "");
  const auto out = dir / "o.mbtiles";
  auto r = run(tiler() + " terrain " + dem + " -o " + out.string(), dir.path());
  expect_failure(r, 1, "dem.tif: no CRS found; pass --s_srs", out);
  auto ok =
      run(tiler() + " terrain -q --s_srs EPSG:4326 " + dem + " -o " + out.string(), dir.path());
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

TEST(TerrainCli, AllNodata) {
  TempDir dir;
  const auto path = (dir / "empty.tif").string();
  const double nodata = -9999;
  write_dem(
      path, 32, 32, kGeoGt, "EPSG:4326", GDT_Float32, [](int, int) { return -9999.0; }, &nodata);
  auto r = run(tiler() + " terrain " + path + " -o " + (dir / "o.mbtiles").string(), dir.path());
  expect_failure(r, 1, "empty.tif: holds no valid data", dir / "o.mbtiles");
}

TEST(TerrainCli, BboxOutsideTheData) {
  TempDir dir;
  const auto dem = good_dem(dir);
  auto r =
      run(tiler() + " terrain " + dem + " --bbox 100,10,101,11 -o " + (dir / "o.mbtiles").string(),
          dir.path());
  expect_failure(r, 1, "--bbox does not intersect the data", dir / "o.mbtiles");
}

TEST(TerrainCli, ZoomOutOfRange) {
  TempDir dir;
  const auto dem = good_dem(dir);
  auto r = run(tiler() + " terrain " + dem + " --max-zoom 40 -o " + (dir / "o.mbtiles").string(),
               dir.path());
  expect_failure(r, 2, "--max-zoom: 40 is out of range", dir / "o.mbtiles");
  r = run(tiler() + " terrain " + dem + " --max-zoom 23 -o " + (dir / "o.mbtiles").string(),
          dir.path());
  expect_failure(r, 2, "is out of range: the data's finest zoom is", dir / "o.mbtiles");
  r = run(
      tiler() + " terrain " + dem + " --min-zoom 9 --max-zoom 5 -o " + (dir / "o.mbtiles").string(),
      dir.path());
  expect_failure(r, 2, "larger than", dir / "o.mbtiles");
}

TEST(TerrainCli, UnwritableOutputPath) {
  TempDir dir;
  const auto dem = good_dem(dir);
  const auto out = dir / "no-such-dir" / "o.mbtiles";
  auto r = run(tiler() + " terrain " + dem + " -o " + out.string(), dir.path());
  expect_failure(r, 3, "o.mbtiles", out);
}

TEST(TerrainCli, ExistingOutputNeedsForce) {
  TempDir dir;
  const auto dem = good_dem(dir);
  const auto out = dir / "o.mbtiles";
  std::ofstream(out) << "keep me";
  auto r = run(tiler() + " terrain " + dem + " -o " + out.string(), dir.path());
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find("pass --force"), std::string::npos) << r.err;
  // Refused before any plan or work is announced: the one line is the error.
  EXPECT_EQ(r.err.find("input(s)"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(read_file(out), "keep me");
  auto forced = run(tiler() + " terrain -q --force " + dem + " -o " + out.string(), dir.path());
  EXPECT_EQ(forced.exit_code, 0) << forced.err;
  EXPECT_NE(read_file(out), "keep me");
}

TEST(TerrainCli, UsageErrors) {
  TempDir dir;
  auto r = run(tiler() + " terrain --frobnicate x.tif -o o.mbtiles", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown option --frobnicate"), std::string::npos);
  r = run(tiler() + " terrain x.tif", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("add -o"), std::string::npos);
  r = run(tiler() + " terrain x.tif -o o.mbtiles --block-size 100", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  r = run(tiler() + " terrain --help", dir.path());
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("--tiling"), std::string::npos);
}

TEST(TerrainCli, JsonProgressIsOneObjectPerLine) {
  TempDir dir;
  const auto dem = good_dem(dir);
  auto r = run(tiler() + " terrain --progress json " + dem + " -o " + (dir / "o.mbtiles").string(),
               dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream lines(r.err);
  int phases = 0;
  for (std::string line; std::getline(lines, line);) {
    EXPECT_EQ(line.front(), '{') << line;
    EXPECT_EQ(line.back(), '}') << line;
    if (line.find("\"phase\"") != std::string::npos &&
        line.find("\"final\":true") != std::string::npos)
      ++phases;
  }
  EXPECT_GT(phases, 3);
}

TEST(TerrainCli, InspectionCommandsRejectNonPackages) {
  TempDir dir;
  std::ofstream(dir / "x.mbtiles") << "text";
  auto r = run(tiler() + " info " + (dir / "x.mbtiles").string(), dir.path());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("x.mbtiles"), std::string::npos);
  r = run(tiler() + " validate " + (dir / "missing.mbtiles").string(), dir.path());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("missing.mbtiles: no such file"), std::string::npos);
}
