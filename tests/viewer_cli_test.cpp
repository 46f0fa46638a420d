// globe-view as a user runs it: headless snapshots against expected PNGs
// (tolerance; the diff image is kept on failure), OSMesa and EGL agreement,
// the memory budget on a flight, and bad input.
#include <gtest/gtest.h>

#include <cstring>

#include <gdal.h>

#include <cmath>
#include <fstream>

#include "raster_fixtures.hpp"
#include "render_fixtures.hpp"
#include "test_paths.hpp"
#include "test_support.hpp"
#include "tileformat/json.hpp"

namespace {

using namespace globe_test;

const char* kCamera = "--camera=-84.30,36.55,2500,30,65";

// Tiles jacksboro once per build tree (shared_folder).
const std::string& jacksboro_package() {
  static const std::string pkg = [] {
    const fs::path dir = shared_folder("globe-view-cli", [](const fs::path& dir) {
      return run_all({tiler() + " terrain -q " + sample("jacksboro.tif").string() + " -o " +
                      (dir / "jacksboro.mbtiles").string()},
                     dir);
    });
    return (dir / "jacksboro.mbtiles").string();
  }();
  return pkg;
}

TEST(ViewerRender, HillshadeSnapshotMatchesExpected) {
  TempDir dir;
  const RunResult r = run(viewer() + " " + jacksboro_package() + " --snapshot " +
                              (dir / "a.png").string() + " --size 320x180 " + kCamera,
                          dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_image((dir / "a.png").string(), "jacksboro_hillshade");
}

TEST(ViewerRender, ShadingModesMatchExpected) {
  for (const std::string mode : {"elevation", "slope", "aspect"}) {
    TempDir dir;
    const RunResult r =
        run(viewer() + " " + jacksboro_package() + " --snapshot " + (dir / "a.png").string() +
                " --size 320x180 --fit --shading " + mode,
            dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    expect_image((dir / "a.png").string(), "jacksboro_fit_" + mode);
  }
}

TEST(ViewerRender, OsMesaAndEglGiveTheSameImage) {
  TempDir dir;
  for (const std::string platform : {"osmesa", "egl"}) {
    const RunResult r =
        run(viewer() + " " + jacksboro_package() + " --platform " + platform + " --snapshot " +
                (dir / (platform + ".png")).string() + " --size 320x180 " + kCamera,
            dir.path());
    ASSERT_EQ(r.exit_code, 0) << platform << ": " << r.err;
  }
  EXPECT_EQ(read_file(dir / "osmesa.png"), read_file(dir / "egl.png"));
}

TEST(ViewerCli, StatsAreJsonOnStdout) {
  TempDir dir;
  const RunResult r =
      run(viewer() + " " + jacksboro_package() + " --stats --frames 3 --size 160x90 " + kCamera,
          dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* key : {"\"frame_ms\"", "\"terrain_ms\"", "\"triangles\"", "\"patches\"",
                          "\"resident_blocks\"", "\"bytes_read\""})
    EXPECT_NE(r.out.find(key), std::string::npos) << key << " missing in " << r.out;
  EXPECT_EQ(r.out.front(), '{');
}

// --camera heights are above the ellipsoid; a pose below the ground is drawn
// from 20 m above it. The reference ground: gdallocationinfo on the source
// DEM (its pixel, not our blocks).
TEST(ViewerCli, CameraBelowTheGroundIsRaisedAboveIt) {
  TempDir dir;
  const RunResult g =
      run("gdallocationinfo -valonly -wgs84 " + sample("jacksboro.tif").string() + " -84.30 36.55",
          dir.path());
  ASSERT_EQ(g.exit_code, 0) << g.err;
  const double ground = std::stod(g.out);
  for (const char* height : {"-100", "300"}) {
    const RunResult r = run(viewer() + " " + jacksboro_package() +
                                " --stats --frames 1 --size 160x90 --camera=-84.30,36.55," +
                                height + ",30,65 --snapshot " + (dir / "below.png").string(),
                            dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("below the ground"), std::string::npos) << r.err;
    const auto stats = tileformat::JsonValue::parse(r.out);
    const std::string pose = stats.find("camera")->string();
    const double drawn = std::stod(pose.substr(pose.find(',', pose.find(',') + 1) + 1));
    EXPECT_NEAR(drawn, ground + 20, 6) << pose;
    EXPECT_GT(stats.find("ground_fraction")->number(), 0.5) << r.out;
  }
  // Above the ground: drawn as asked, no note.
  const RunResult above =
      run(viewer() + " " + jacksboro_package() + " --stats --frames 1 --size 160x90 " + kCamera,
          dir.path());
  ASSERT_EQ(above.exit_code, 0) << above.err;
  EXPECT_EQ(above.err.find("below the ground"), std::string::npos) << above.err;
  EXPECT_NE(above.out.find("36.5500000,2500.00,30.00,65.00"), std::string::npos) << above.out;
}

// A frame without terrain is written, said on stderr and exits 6.
TEST(ViewerCli, AFrameWithoutTerrainSaysSo) {
  TempDir dir;
  const RunResult r = run(viewer() + " " + jacksboro_package() +
                              " --stats --frames 1 --size 160x90 --camera=10,10,5000,0,0 "
                              "--snapshot " +
                              (dir / "off.png").string(),
                          dir.path());
  EXPECT_EQ(r.exit_code, 6) << r.err;
  EXPECT_NE(r.err.find("the frame shows no terrain"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("\"ground_fraction\": 0.0000"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(dir / "off.png"));
}

TEST(ViewerCli, MemoryBudgetHoldsDuringAFlight) {
  TempDir dir;
  std::ofstream path(dir / "flight.txt");
  for (int i = 0; i <= 12; ++i)
    path << -84.42 + i * 0.03 << "," << 36.45 + i * 0.02 << ",900,45,60\n";
  path.close();
  const RunResult r = run(viewer() + " " + jacksboro_package() +
                              " --stats --frames 1 --size 320x180 --cache-mb 4 --camera-path " +
                              (dir / "flight.txt").string(),
                          dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto number = [&](const std::string& key) {
    const size_t at = r.out.find("\"" + key + "\": ");
    EXPECT_NE(at, std::string::npos) << key;
    return std::stod(r.out.substr(at + key.size() + 4));
  };
  EXPECT_LE(number("max_resident_bytes"), number("budget_bytes"));
  EXPECT_GT(number("evictions"), 0) << "the flight should need more blocks than fit: " << r.out;
}

TEST(ViewerCli, MeshExportIsAPly) {
  TempDir dir;
  const RunResult r = run(viewer() + " " + jacksboro_package() + " --export-mesh " +
                              (dir / "m.ply").string() + " --size 160x90 " + kCamera,
                          dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string ply = read_file(dir / "m.ply");
  EXPECT_EQ(ply.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
  EXPECT_NE(ply.find("element face "), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "m.ply.tmp"));
}

// --globe: the PLY holds geocentric WGS84 coordinates and says so; every
// vertex lies on the ellipsoid (radius), around jacksboro (longitude, and the
// geocentric latitude, 0.19 degrees below the geodetic one there), and some
// right below the camera.
TEST(ViewerCli, GlobeMeshExportIsGeocentric) {
  TempDir dir;
  const RunResult r = run(viewer() + " " + jacksboro_package() + " --globe --export-mesh " +
                              (dir / "m.ply").string() + " --size 160x90 " + kCamera,
                          dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string ply = read_file(dir / "m.ply");
  EXPECT_NE(ply.find("comment globe frame geocentric\n"), std::string::npos);
  const size_t at = ply.find("element vertex ");
  ASSERT_NE(at, std::string::npos);
  const size_t n = std::stoul(ply.substr(at + 15));
  const size_t body = ply.find("end_header\n") + 11;
  ASSERT_GT(n, 100u);
  ASSERT_GE(ply.size(), body + n * 24);
  const double kDeg = 180 / 3.141592653589793;
  bool near_eye = false;
  for (size_t i = 0; i < n; ++i) {
    double v[3];
    std::memcpy(v, ply.data() + body + i * 24, sizeof v);
    const double r_xy = std::hypot(v[0], v[1]), radius = std::hypot(r_xy, v[2]);
    const double lon = std::atan2(v[1], v[0]) * kDeg, lat = std::atan2(v[2], r_xy) * kDeg;
    ASSERT_GT(radius, 6.36e6) << i;
    ASSERT_LT(radius, 6.38e6) << i;
    // Coarse patches reach past the data, up to the minzoom tiles.
    ASSERT_NEAR(lon, -84.2, 12) << i;
    ASSERT_NEAR(lat, 36.55 - 0.19, 12) << i;
    near_eye = near_eye || (std::abs(lon + 84.30) < 0.05 && std::abs(lat - (36.55 - 0.19)) < 0.05);
  }
  EXPECT_TRUE(near_eye) << "no vertex below the camera";
  const RunResult flat = run(viewer() + " " + jacksboro_package() + " --export-mesh " +
                                 (dir / "f.ply").string() + " --size 160x90 " + kCamera,
                             dir.path());
  ASSERT_EQ(flat.exit_code, 0) << flat.err;
  EXPECT_NE(read_file(dir / "f.ply").find("comment globe frame flat\n"), std::string::npos);
}

TEST(ViewerCli, BadInputGetsAClearError) {
  TempDir dir;
  struct Case {
    std::string args, message;
    int code;
  };
  std::ofstream(dir / "text.mbtiles") << "not a database";
  {
    // A valid SQLite package of another kind.
    const RunResult r =
        run("sqlite3 " + (dir / "png.mbtiles").string() +
                " \"CREATE TABLE metadata (name TEXT, value TEXT); INSERT INTO "
                "metadata VALUES ('format', 'png'); CREATE TABLE tiles (zoom_level INTEGER, "
                "tile_column INTEGER, tile_row INTEGER, tile_data BLOB);\"",
            dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const std::string snap = " --snapshot " + (dir / "out.png").string();
  const Case cases[] = {
      {(dir / "missing.mbtiles").string() + snap, "missing.mbtiles", 1},
      {(dir / "text.mbtiles").string() + snap, "text.mbtiles", 1},
      // Alone, an image goes over a flat base; this one lacks its zooms.
      {(dir / "png.mbtiles").string() + snap, "png.mbtiles: metadata key minzoom is missing", 1},
      {jacksboro_package() + snap + " --shading imagery", "--shading imagery", 2},
      {jacksboro_package() + snap + " --image-opacity 0.5", "--image-opacity", 2},
      {jacksboro_package() + " " + (dir / "png.mbtiles").string() + snap + " --image-opacity 2",
       "--image-opacity", 2},
      {jacksboro_package() + snap + " --camera 1,2,3", "--camera", 2},
      {jacksboro_package() + snap + " --shading sepia", "--shading", 2},
      {jacksboro_package() + " --snapshot " + (dir / "no/such/dir/x.png").string(), "x.png", 3},
  };
  std::vector<std::pair<std::string, Case>> runs;
  for (const Case& c : cases)
    runs.push_back({viewer() + " " + c.args, c});
  // In plain words: what the file is and what is needed, no SQL or MIME types.
  runs.push_back({viewer() + " " + (dir / "text.mbtiles").string() + snap,
                  {"", "text.mbtiles: not a tile package: not an SQLite file", 1}});
  runs.push_back({tiler() + " analyze " + (dir / "png.mbtiles").string() + " -o " +
                      (dir / "a.mbtiles").string(),
                  {"", "png.mbtiles: an image package, where a terrain package is needed", 1}});
  // A window without a display is a usage error.
  runs.push_back({"env -u DISPLAY -u WAYLAND_DISPLAY " + viewer() + " " + jacksboro_package(),
                  {"", "no display to open a window on", 2}});
  for (const auto& [command, c] : runs) {
    const RunResult r = run(command, dir.path());
    EXPECT_EQ(r.exit_code, c.code) << command << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << command << "\n" << r.err;
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("[SQL"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("PRAGMA"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("application/"), std::string::npos) << r.err;
  }
  EXPECT_FALSE(fs::exists(dir / "out.png"));
}

// Every program and command answers --version on stdout, and a usage error
// points to --help once.
TEST(ViewerCli, EveryProgramTellsItsVersion) {
  TempDir dir;
  const std::string version = globe_test::paths::project_version();
  const std::pair<std::string, std::string> programs[] = {
      {viewer(), "globe-view"},
      {globe_test::paths::serve(), "globe-serve"},
      {tiler(), "globe-tiler"},
      {tiler() + " terrain", "globe-tiler"},
      {vectorize() + " lines", "globe-vectorize"}};
  for (const auto& [command, name] : programs) {
    const RunResult r = run(command + " --version", dir.path());
    EXPECT_EQ(r.exit_code, 0) << command << ": " << r.err;
    EXPECT_EQ(r.out, name + " " + version + "\n") << command;
    if (command == tiler()) continue;  // a command is expected first
    const RunResult bad = run(command + " x --no-such-option", dir.path());
    EXPECT_EQ(bad.exit_code, 2) << command;
    const size_t hint = bad.err.find("--help");
    EXPECT_NE(hint, std::string::npos) << bad.err;
    EXPECT_EQ(bad.err.find("--help", hint + 1), std::string::npos) << "hint twice: " << bad.err;
  }
}

// An idle window draws on demand: once loaded and left alone it sleeps (was
// a full core, drawing the same frame 60 times a second), and still answers
// a key.
TEST(ViewerIdleWindow, SleepsUntilSomethingHappens) {
  TempDir dir;
  const RunResult r =
      run("xvfb-run -a -s '-screen 0 640x480x24' " + globe_test::paths::test_data_dir() +
              "/window/idle_cpu.sh " + dir.path().string() + " 3 " + viewer() +
              " --platform glfw --size 320x180 " + jacksboro_package(),
          dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err << read_file(dir / "viewer.stderr");
  const size_t at = r.out.find("cpu_seconds ");
  ASSERT_NE(at, std::string::npos) << r.out;
  const double cpu = std::stod(r.out.substr(at + 12));
  std::printf("idle window: %.2f CPU s in 3 s\n", cpu);
  EXPECT_LT(cpu, 0.3) << "an idle window should sleep (" << cpu << " CPU s in 3 s)";
}

TEST(ViewerCli, CorruptTileWarnsAndDrawsCoarser) {
  TempDir dir;
  const std::string pkg = (dir / "broken.mbtiles").string();
  fs::copy_file(jacksboro_package(), pkg);
  // Corrupt every tile of the finest zoom (each has its own blob).
  const RunResult s = run("sqlite3 " + pkg +
                              " \"UPDATE blobs SET tile_data = randomblob(100) WHERE blob_id IN "
                              "(SELECT blob_id FROM map WHERE zoom_level = (SELECT MAX(zoom_level) "
                              "FROM map));\"",
                          dir.path());
  ASSERT_EQ(s.exit_code, 0) << s.err;
  const RunResult r = run(viewer() + " " + pkg + " --stats --frames 1 --size 320x180 " + kCamera +
                              " --snapshot " + (dir / "a.png").string(),
                          dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("\"broken_tiles\": 0,"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("\"patches\": 0,"), std::string::npos) << "nothing drawn: " << r.out;
  EXPECT_TRUE(fs::exists(dir / "a.png"));
}

}  // namespace
