// The hostile-input corpus (tests/data/hostile/make_hostile.sh): every input
// gets its documented outcome (docs/robustness.md "Hostile inputs"), a clear
// error or correct output, never a crash or a hang (each run has a timeout).
#include <gtest/gtest.h>

#include "render_fixtures.hpp"
#include "test_paths.hpp"
#include "test_support.hpp"

using namespace globe_test;

namespace {

class Hostile : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const fs::path script =
        fs::path(globe_test::paths::test_data_dir()) / "hostile" / "make_hostile.sh";
    inputs_ = new fs::path(shared_folder(
        "globe-hostile",
        [&](const fs::path& dir) {
          const std::string t = (dir / "t.mbtiles").string(), l = (dir / "l.mbtiles").string();
          return run_all(
              {tiler() + " terrain " + sample("jacksboro.tif").string() + " -q -o " + t,
               vectorize() + " lines " + sample("os_wales_contours.shp").string() + " -q -o " + l,
               "bash " + script.string() + " " + (dir / "corpus").string() + " " + t + " " + l},
              dir);
        },
        {script}));
    dir_ = new fs::path(run_scratch_dir("globe-hostile"));
  }
  static void TearDownTestSuite() {
    std::error_code ec;
    fs::remove_all(*dir_, ec);
    delete dir_;
    delete inputs_;
  }
  // The corpus and the packages it was made from (shared by the tests, never
  // changed); what a test writes goes under dir_.
  static std::string terrain() { return (*inputs_ / "t.mbtiles").string(); }
  static fs::path corpus() { return *inputs_ / "corpus"; }
  static std::string in(const std::string& name) { return (corpus() / name).string(); }
  static std::string out(const std::string& name) { return (*dir_ / name).string(); }
  // Runs with a time limit: a hang fails the test (timeout's exit code 124).
  static RunResult limited(const std::string& command, int seconds = 120) {
    return run("timeout " + std::to_string(seconds) + " " + command, *dir_);
  }
  static fs::path* inputs_;
  static fs::path* dir_;
};
fs::path* Hostile::inputs_ = nullptr;
fs::path* Hostile::dir_ = nullptr;

void expect_error(const RunResult& r, int code, const std::string& file, const std::string& why) {
  EXPECT_EQ(r.exit_code, code) << r.err;
  EXPECT_NE(r.err.find(file), std::string::npos)
      << "the message should name " << file << ": " << r.err;
  EXPECT_NE(r.err.find(why), std::string::npos) << r.err;
}

int tiles_at(const std::string& package, int z, const fs::path& scratch) {
  const RunResult r = run("sqlite3 " + package + " 'SELECT COUNT(*) FROM map WHERE zoom_level = " +
                              std::to_string(z) + "'",
                          scratch);
  return r.exit_code == 0 ? std::stoi(r.out) : -1;
}

}  // namespace

TEST_F(Hostile, RasterHeaderClaimingAnAbsurdSizeIsRefused) {
  expect_error(
      limited(tiler() + " terrain " + in("absurd_size.raw") + " -q -o " + out("a.mbtiles")), 1,
      "absurd_size.raw", "too small");
  EXPECT_FALSE(fs::exists(out("a.mbtiles")));
}

TEST_F(Hostile, MicroscopicPixelsGiveNoDataError) {
  expect_error(
      limited(tiler() + " terrain " + in("absurd_pixel.raw") + " -q -o " + out("p.mbtiles")), 1,
      "absurd_pixel.raw", "no tile holds valid data");
}

TEST_F(Hostile, NanAndInfiniteHeightsAreHoles) {
  const std::string o = out("nan.mbtiles");
  const RunResult r = limited(tiler() + " terrain " + in("nan_inf.raw") + " -q -o " + o);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const RunResult v = run(tiler() + " validate " + o, *dir_);
  EXPECT_EQ(v.exit_code, 0) << v.out << v.err;
}

TEST_F(Hostile, AllNanDemIsANoDataError) {
  expect_error(limited(tiler() + " terrain " + in("all_nan.raw") + " -q -o " + out("n.mbtiles")), 1,
               "all_nan.raw", "holds no valid data");
}

TEST_F(Hostile, OnePixelDemBuildsAValidPackage) {
  const std::string o = out("one.mbtiles");
  ASSERT_EQ(limited(tiler() + " terrain " + in("one_pixel.raw") + " -q -o " + o).exit_code, 0);
  EXPECT_EQ(run(tiler() + " validate " + o, *dir_).exit_code, 0);
}

TEST_F(Hostile, DemAcrossTheAntimeridianFillsBothEdges) {
  const std::string o = out("anti.mbtiles");
  ASSERT_EQ(limited(tiler() + " terrain " + in("antimeridian.raw") + " -q -o " + o).exit_code, 0);
  EXPECT_EQ(run(tiler() + " validate " + o, *dir_).exit_code, 0);
  // 0.1 degree pixels: zoom 4 at least, with tiles in the first and last column.
  const RunResult z =
      run("sqlite3 " + o + " \"SELECT value FROM metadata WHERE name='maxzoom'\"", *dir_);
  const int maxzoom = std::stoi(z.out);
  EXPECT_GE(maxzoom, 4);
  const std::string edge =
      "sqlite3 " + o + " \"SELECT COUNT(*) FROM map WHERE zoom_level = " + std::to_string(maxzoom) +
      " AND tile_column = ";
  EXPECT_GT(std::stoi(run(edge + "0\"", *dir_).out), 0);
  EXPECT_GT(std::stoi(run(edge + std::to_string((1 << maxzoom) - 1) + "\"", *dir_).out), 0);
}

TEST_F(Hostile, DemCoveringThePolesIsClippedToWebMercator) {
  const std::string o = out("poles.mbtiles");
  ASSERT_EQ(limited(tiler() + " terrain " + in("poles.raw") + " -q -o " + o).exit_code, 0);
  EXPECT_EQ(run(tiler() + " validate " + o, *dir_).exit_code, 0);
  EXPECT_EQ(tiles_at(o, 1, *dir_), 4);  // the whole square world
}

TEST_F(Hostile, ShapefilesWithABrokenIndexAreRefused) {
  expect_error(
      limited(vectorize() + " lines " + in("shx_garbage.shp") + " -q -o " + out("g.mbtiles")), 1,
      "shx_garbage.shp", "not vector data");
  expect_error(
      limited(vectorize() + " lines " + in("shx_truncated.shp") + " -q -o " + out("c.mbtiles")), 1,
      "shx_truncated.shp", ".shx");
  expect_error(
      limited(vectorize() + " lines " + in("shx_missing.shp") + " -q -o " + out("m.mbtiles")), 1,
      "shx_missing.shp", "index (.shx) is missing");
  for (const char* o : {"g.mbtiles", "c.mbtiles", "m.mbtiles"})
    EXPECT_FALSE(fs::exists(out(o)));
}

TEST_F(Hostile, LineWithAMillionVerticesIsTiled) {
  const std::string o = out("million.mbtiles");
  const RunResult r =
      limited(vectorize() + " lines " + in("million_vertices.geojson") + " -o " + o, 600);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("1 features (0 skipped"), std::string::npos) << r.err;
  EXPECT_EQ(run(vectorize() + " validate " + o, *dir_).exit_code, 0);
}

TEST_F(Hostile, CoordinatesOffTheGlobeAreSkippedAndCounted) {
  const RunResult r =
      limited(vectorize() + " lines " + in("out_of_range.geojson") + " -o " + out("range.mbtiles"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("1 features (3 skipped, 3 invalid"), std::string::npos) << r.err;
  expect_error(limited(vectorize() + " lines " + in("only_out_of_range.geojson") + " -q -o " +
                       out("none.mbtiles")),
               1, "only_out_of_range.geojson", "no feature with usable line");
}

TEST_F(Hostile, PackagesOfRandomTilesAreReportedNotFollowed) {
  // validate reports every tile on stdout (its data) and fails.
  for (const std::string& cmd : {tiler() + " validate " + in("random_terrain.mbtiles"),
                                 vectorize() + " validate " + in("random_lines.mbtiles")}) {
    const RunResult r = limited(cmd);
    EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
    EXPECT_NE(r.out.find("bad magic"), std::string::npos) << r.out;
  }
  // The viewer warns and draws what it can: here nothing, which it says (exit 6).
  const RunResult v = limited(viewer() + " " + in("random_terrain.mbtiles") + " --snapshot " +
                              out("r.png") + " --size 160x90");
  EXPECT_EQ(v.exit_code, 6) << v.err;
  EXPECT_NE(v.err.find("warning"), std::string::npos) << v.err;
  EXPECT_NE(v.err.find("its tiles could not be read"), std::string::npos) << v.err;
  const RunResult vl = limited(viewer() + " " + terrain() + " " + in("random_lines.mbtiles") +
                               " --snapshot " + out("rl.png") + " --size 160x90");
  EXPECT_EQ(vl.exit_code, 0) << vl.err;
}

TEST_F(Hostile, FilesThatAreNotPackagesAreRefused) {
  for (const char* name : {"not_a_package.mbtiles", "truncated.mbtiles"}) {
    expect_error(limited(tiler() + " info " + in(name)), 1, name, "not a tile package");
    expect_error(limited(viewer() + " " + in(name) + " --snapshot " + out("x.png")), 1, name,
                 "not a tile package");
  }
}
