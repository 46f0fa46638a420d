// globe-view as a web client (docs/viewer.md "Remote sources"): the same
// picture from the network as from the files, through every kind of source a
// user points it at —
//   globe-serve's TileJSON (terrain, imagery, lines, points, areas; both
//   global tilings; globe and flat), an XYZ folder and a PMTiles archive of
//   imagery on a plain static server (tests/support/fault_server, not
//   globe-serve), and a TileJSON with the package's own tiles written into a
//   folder by this test (sqlite3, not the project's reader);
// and the behaviour a server operator expects: a bad network waited out
// (5xx, 429 with Retry-After, truncated and reset bodies), nothing broken
// cached, the disk cache's cap held, --offline from the cache, revalidation
// across runs, and no tile asked for that the source says is not there.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "fault_server_fixtures.hpp"
#include "point_fixtures.hpp"
#include "render_fixtures.hpp"
#include "serve_fixtures.hpp"
#include "test_paths.hpp"
#include "test_support.hpp"

namespace {

using namespace globe_test;

// Small packages of every kind, in both global tilings.
fs::path packages() {
  return shared_folder("remote", [](const fs::path& dir) {
    write_places_csv((dir / "p.csv").string(), {"n"},
                     {{"a", 7.4, 46.9, {10}},
                      {"b", -74, 40.7, {20}},
                      {"c", 139.7, 35.7, {30}},
                      {"d", -43.2, -22.9, {40}},
                      {"e", 18.4, -33.9, {25}}});
    std::vector<std::string> cmds;
    for (const std::string t : {"webmercator", "geodetic"}) {
      const std::string o = " --tiling " + t + " -o " + (dir / t).string();
      cmds.push_back(tiler() + " terrain -q " + sample("etopo20.tif").string() + " --max-zoom 3" +
                     o + "-terrain.mbtiles");
      cmds.push_back(tiler() + " imagery -q " + sample("bluemarble.tif").string() +
                     " --max-zoom 3" + o + "-image.mbtiles");
      cmds.push_back(vectorize() + " lines -q " + sample("ne_admin1.shp").string() +
                     " --max-zoom 4" + o + "-lines.mbtiles");
      cmds.push_back(vectorize() + " points -q " + (dir / "p.csv").string() +
                     " --xy lon,lat --fields n --max-zoom 4" + o + "-points.mbtiles");
      cmds.push_back(vectorize() + " areas -q " + sample("world.gpkg").string() + " --max-zoom 3" +
                     o + "-areas.mbtiles");
    }
    cmds.push_back(tiler() + " export -q " + (dir / "webmercator-image.mbtiles").string() + " -o " +
                   (dir / "xyz").string());
    cmds.push_back(tiler() + " export -q " + (dir / "webmercator-image.mbtiles").string() + " -o " +
                   (dir / "image.pmtiles").string());
    return run_all(cmds, dir);
  });
}

std::string pkg(const std::string& tiling, const std::string& kind) {
  return (packages() / (tiling + "-" + kind + ".mbtiles")).string();
}

// globe-view ARGS --snapshot OUT (headless, small); the run's result.
RunResult snapshot(const std::string& args, const fs::path& out, const fs::path& scratch) {
  return run(viewer() + " " + args + " --size 256x160 --snapshot " + out.string(), scratch);
}

bool same_file(const fs::path& a, const fs::path& b) {
  return fs::exists(a) && fs::exists(b) && read_file(a) == read_file(b);
}

// The "network" object of a --stats line, as numbers by name.
std::map<std::string, long long> network_stats(const std::string& out) {
  std::map<std::string, long long> m;
  const size_t at = out.find("\"network\": {");
  if (at == std::string::npos) return m;
  const std::string obj = out.substr(at, out.find('}', at) - at);
  static const std::regex kv("\"([a-z_]+)\": ([0-9]+)");
  for (std::sregex_iterator it(obj.begin(), obj.end(), kv), end; it != end; ++it)
    m[(*it)[1]] = std::stoll((*it)[2]);
  return m;
}

struct View {
  std::string name, tiling, kinds, mode;  // kinds: "terrain,image,..."; mode: --globe / --flat
};
void PrintTo(const View& v, std::ostream* os) {
  *os << v.name;
}

class ViewerRemote : public ::testing::TestWithParam<View> {};

// The same packages, from the files and from globe-serve's TileJSON: the same
// picture, byte for byte (the tiles are the same bytes, decoded alike).
TEST_P(ViewerRemote, GlobeServeGivesThePictureOfTheFiles) {
  const View& v = GetParam();
  TempDir dir;
  std::vector<std::string> files, args;
  std::stringstream kinds(v.kinds);
  for (std::string k; std::getline(kinds, k, ',');)
    files.push_back(pkg(v.tiling, k));
  ServeProcess serve(files, dir.path());
  ASSERT_GT(serve.port(), 0) << read_file(dir / "serve.log");
  std::string local = v.mode, remote = v.mode + " --cache-dir " + (dir / "cache").string();
  for (const std::string& f : files) {
    local += " " + f;
    remote += " http://127.0.0.1:" + std::to_string(serve.port()) + "/" +
              fs::path(f).stem().string() + ".json";
  }
  const RunResult a = snapshot(local, dir / "local.png", dir.path());
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const RunResult b = snapshot(remote, dir / "remote.png", dir.path());
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_TRUE(same_file(dir / "local.png", dir / "remote.png"))
      << "the remote sources drew another picture; see " << dir.path();
}

INSTANTIATE_TEST_SUITE_P(
    Kinds, ViewerRemote,
    ::testing::Values(
        View{"terrain_image_globe_wm", "webmercator", "terrain,image", "--globe"},
        View{"terrain_image_flat_geo", "geodetic", "terrain,image", "--flat"},
        View{"lines_points_areas_globe_geo", "geodetic", "terrain,areas,lines,points", "--globe"},
        View{"lines_points_areas_flat_wm", "webmercator", "terrain,areas,lines,points", "--flat"}),
    [](const auto& info) { return info.param.name; });

// Imagery on a plain static server, as the web publishes it: an XYZ folder
// (with and without the zooms given) and a PMTiles archive read by ranges.
TEST(ViewerRemoteForeign, XyzFolderAndPmtilesDrawLikeThePackage) {
  TempDir dir;
  FaultServer server(packages(), {}, dir.path());
  ASSERT_GT(server.port(), 0);
  const std::string terrain = pkg("webmercator", "terrain");
  ASSERT_EQ(snapshot(terrain + " " + pkg("webmercator", "image"), dir / "local.png", dir.path())
                .exit_code,
            0);
  const std::string cache = " --cache-dir " + (dir / "cache").string();
  for (const auto& [name, source] : std::vector<std::pair<std::string, std::string>>{
           {"xyz", "'" + server.url("/xyz/{z}/{x}/{y}.png") + "' --source-zooms 0-3"},
           {"xyz_deeper", "'" + server.url("/xyz/{z}/{x}/{y}.png") + "'"},
           {"pmtiles", server.url("/image.pmtiles")}}) {
    const RunResult r = snapshot(terrain + " " + source + cache, dir / (name + ".png"), dir.path());
    ASSERT_EQ(r.exit_code, 0) << name << ": " << r.err;
    EXPECT_TRUE(same_file(dir / "local.png", dir / (name + ".png"))) << name;
  }
  server.stop();
  // Zoom 4 and deeper are 404s there: each asked once at most, never again.
  std::map<std::string, int> asked;
  for (const LogEntry& e : server.log())
    if (e.status == 404) ++asked[e.path];
  for (const auto& [path, n] : asked)
    EXPECT_EQ(n, 1) << path << " asked " << n << " times";
}

// Elevation as the web publishes it — the project's own Terrarium,
// Terrain-RGB and quantized-mesh exports of the terrain, on a static server
// that is not globe-serve — draws like the package: coloured by height
// (a fixed range), flat and straight down, the pictures within a PSNR the
// exports' resampling and TIN error allow (measured: quantized-mesh 28.8 dB;
// Terrarium and Terrain-RGB 24.6 dB, resampled twice — the export's pixel
// centres, the viewer's pixel corners). The same tiles decoded in the other
// encoding give 6.6 dB (the check can fail).
TEST(ViewerRemoteForeign, TerrariumTerrainRgbAndQuantizedMeshDrawLikeThePackage) {
  TempDir dir;
  const std::string terrain = pkg("webmercator", "terrain");
  const fs::path www = dir / "www";
  ASSERT_TRUE(run_all(
      {tiler() + " export -q " + terrain + " --format terrarium -o " + (www / "terrarium").string(),
       tiler() + " export -q " + terrain + " --format terrain-rgb -o " + (www / "rgb").string(),
       tiler() + " export -q " + terrain + " --format quantized-mesh -o " + (www / "qm").string()},
      dir.path()));
  FaultServer server(www, {}, dir.path());
  ASSERT_GT(server.port(), 0);
  // The finest zoom everywhere (a tiny screen-space error): the data are
  // compared, not the LOD's choices, which differ by design (a package's
  // error trees know the finer data; a remote source's blocks do not).
  const std::string view =
      " --flat --camera 10,46,1500000,0,0 --max-error-px 0.05 --shading elevation "
      "--height-range -3000,4000 --cache-dir " +
      (dir / "cache").string();
  ASSERT_EQ(snapshot(terrain + view, dir / "local.png", dir.path()).exit_code, 0);
  int w = 0, h = 0;
  const std::vector<uint8_t> local = read_rgb((dir / "local.png").string(), w, h);
  struct Case {
    std::string name, source;
    double min_psnr, max_psnr;
  };
  for (const Case& c :
       std::vector<Case>{{"terrarium",
                          "'" + server.url("/terrarium/{z}/{x}/{y}.png") +
                              "' --dem-encoding terrarium --source-zooms 0-3",
                          22, 99},
                         {"terrarium_tilejson", server.url("/terrarium/metadata.json"), 22, 99},
                         {"terrain_rgb",
                          "'" + server.url("/rgb/{z}/{x}/{y}.png") +
                              "' --dem-encoding terrain-rgb --source-zooms 0-3",
                          22, 99},
                         {"quantized_mesh", server.url("/qm/layer.json"), 24, 99},
                         {"wrong_encoding",
                          "'" + server.url("/terrarium/{z}/{x}/{y}.png") +
                              "' --dem-encoding terrain-rgb --source-zooms 0-3",
                          0, 15}}) {
    const fs::path out = dir / (c.name + ".png");
    const RunResult r = snapshot(c.source + view, out, dir.path());
    ASSERT_EQ(r.exit_code, 0) << c.name << ": " << r.err;
    int w2 = 0, h2 = 0;
    const std::vector<uint8_t> got = read_rgb(out.string(), w2, h2);
    ASSERT_EQ(got.size(), local.size()) << c.name;
    const double p = psnr(local, got);
    EXPECT_GE(p, c.min_psnr) << c.name;
    EXPECT_LE(p, c.max_psnr) << c.name;
    std::cerr << c.name << ": PSNR " << p << " dB against the package\n";
  }
}

// A folder holding a package's own tiles and a TileJSON with its "globe"
// member, written here from the package with sqlite3 (not the project's
// reader): what globe-serve publishes, on a server that is not globe-serve.
// Only the zooms and tile ranges of `zooms` are announced.
void write_native_folder(const std::string& package, const fs::path& root, const std::string& name,
                         int max_zoom, const fs::path& scratch) {
  const fs::path tiles = root / name;
  fs::create_directories(tiles);
  const RunResult meta =
      run("sqlite3 -separator '\t' " + package + " 'select name, value from metadata'", scratch);
  ASSERT_EQ(meta.exit_code, 0) << meta.err;
  std::string metadata;
  std::istringstream lines(meta.out);
  for (std::string line; std::getline(lines, line);) {
    const size_t tab = line.find('\t');
    if (tab == std::string::npos) continue;
    std::string value = line.substr(tab + 1), escaped;
    for (char c : value) {
      if (c == '"' || c == '\\') escaped += '\\';
      escaped += c;
    }
    metadata += std::string(metadata.empty() ? "" : ",") + "\"" + line.substr(0, tab) + "\":\"" +
                escaped + "\"";
  }
  // Each tile to its file: sqlite3's writefile(), rows turned to XYZ.
  const RunResult dump = run(
      "cd " + tiles.string() + " && sqlite3 " + package +
          " \"select zoom_level, tile_column, (1 << zoom_level) - 1 - tile_row from tiles where "
          "zoom_level <= " +
          std::to_string(max_zoom) +
          "\" | while IFS='|' read z x y; do "
          "mkdir -p $z/$x; done && sqlite3 " +
          package +
          " \"select writefile(zoom_level || '/' || tile_column || '/' || ((1 << zoom_level) - 1 - "
          "tile_row) || '.globe', tile_data) from tiles where zoom_level <= " +
          std::to_string(max_zoom) + "\" > /dev/null",
      scratch);
  ASSERT_EQ(dump.exit_code, 0) << dump.err;
  // Announced ranges per zoom (geodetic has two columns at zoom 0).
  const RunResult ranges = run(
      "sqlite3 " + package +
          " \"select zoom_level, min(tile_column), max(tile_column), min((1 << zoom_level) - 1 - "
          "tile_row), max((1 << zoom_level) - 1 - tile_row) from tiles where zoom_level <= " +
          std::to_string(max_zoom) + " group by zoom_level\"",
      scratch);
  std::string zooms;
  std::istringstream rl(ranges.out);
  for (std::string line; std::getline(rl, line);) {
    std::replace(line.begin(), line.end(), '|', ',');
    zooms += std::string(zooms.empty() ? "" : ",") + "[" + line + "]";
  }
  // The tiles' URL relative to the TileJSON, as TileJSON allows.
  std::ofstream(root / (name + ".json"))
      << "{\"tilejson\":\"3.0.0\",\"tiles\":[],\"globe\":{\"tiles\":[\"" << name
      << "/{z}/{x}/{y}.globe\"],\"zooms\":[" << zooms << "],\"metadata\":{" << metadata << "}}}";
}

// The network a user complains about: latency, 500s, a 429 with
// Retry-After, a truncated body, a connection reset mid-body, a slow drip —
// on the terrain's and the imagery's tiles. The picture is the files' one;
// the 429 is waited out (no request to the host before Retry-After); a
// broken tile (wrong content type) is reported, drawn from its neighbours,
// and not cached: the next run, on a good network, asks for it again and
// draws the files' picture from the cache and that one tile.
TEST(ViewerRemoteNetwork, BadNetworkIsWaitedOutAndNothingBrokenIsCached) {
  TempDir dir;
  const fs::path root = dir / "www";
  write_native_folder(pkg("webmercator", "terrain"), root, "terrain", 3, dir.path());
  fs::copy(packages() / "xyz", root / "xyz", fs::copy_options::recursive);
  ASSERT_FALSE(HasFailure());
  // Faults on exact tiles, each for the first request(s) only.
  std::ofstream(root / ".faults") << "/terrain/1/0/0.globe 500 2\n"
                                     "/terrain/1/1/0.globe 429 1\n"
                                     "/terrain/1/0/1.globe truncate 1\n"
                                     "/terrain/1/1/1.globe reset 1\n"
                                     "/xyz/1/1/1.png 500 1\n"
                                     "/xyz/1/0/1.png wrongtype 1\n";
  const std::string cache = (dir / "cache").string();
  const std::string local = pkg("webmercator", "terrain") + " " + pkg("webmercator", "image");
  ASSERT_EQ(snapshot(local + " --globe", dir / "local.png", dir.path()).exit_code, 0);
  FaultServer server(root, {"--latency", "20:80", "--retry-after", "1"}, dir.path());
  ASSERT_GT(server.port(), 0);
  const std::string remote = server.url("/terrain.json") + " '" +
                             server.url("/xyz/{z}/{x}/{y}.png") +
                             "' --source-zooms 0-3 --globe --cache-dir " + cache;
  const RunResult bad = run(
      viewer() + " " + remote + " --size 256x160 --stats --snapshot " + (dir / "bad.png").string(),
      dir.path());
  ASSERT_EQ(bad.exit_code, 0) << bad.err;
  auto stats = network_stats(bad.out);
  EXPECT_GE(stats["retries"], 5) << bad.out;
  EXPECT_EQ(stats["broken"], 1) << bad.out;
  EXPECT_NE(bad.err.find("/xyz/1/0/1.png"), std::string::npos) << bad.err;
  // The same server, its faults spent: the cached tiles are revalidated, the
  // broken one (never cached) asked again, and the picture is the files'.
  const RunResult good = snapshot(remote, dir / "good.png", dir.path());
  ASSERT_EQ(good.exit_code, 0) << good.err;
  EXPECT_TRUE(same_file(dir / "local.png", dir / "good.png"));
  server.stop();
  const std::vector<LogEntry> log = server.log();
  EXPECT_EQ(count_path(log, "/xyz/1/0/1.png"), 2u);
  // No request to the host within Retry-After of the 429 (those sent before
  // its answer arrived aside).
  const auto throttled =
      std::find_if(log.begin(), log.end(), [](const LogEntry& e) { return e.status == 429; });
  ASSERT_NE(throttled, log.end());
  for (const LogEntry& e : log) {
    if (e.t > throttled->done + 0.05 && e.t < throttled->done + 5) {
      EXPECT_GE(e.t, throttled->done + 0.95) << e.path << " asked during the 429's hold";
    }
  }
}

// The disk cache: --offline draws the same picture from it; a restart
// revalidates (If-None-Match, 304); a long flight under a small cap leaves
// the file within the cap; tiles outside the source's announced ranges are
// never asked for.
TEST(ViewerRemoteCache, OfflineRevalidationCapAndAvailability) {
  TempDir dir;
  const fs::path root = dir / "www";
  write_native_folder(pkg("geodetic", "terrain"), root, "terrain", 3, dir.path());
  fs::copy(packages() / "xyz", root / "xyz", fs::copy_options::recursive);
  ASSERT_FALSE(HasFailure());
  const std::string cache = (dir / "cache").string();
  FaultServer server(root, {"--max-age", "0"}, dir.path());
  ASSERT_GT(server.port(), 0);
  const std::string sources = server.url("/terrain.json") + " '" +
                              server.url("/xyz/{z}/{x}/{y}.png") + "' --source-zooms 0-3";
  const RunResult first = snapshot(sources + " --cache-dir " + cache, dir / "a.png", dir.path());
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const size_t asked_first = server.log().size();
  // Offline: no request, the same picture.
  const RunResult offline =
      snapshot(sources + " --offline --cache-dir " + cache, dir / "b.png", dir.path());
  ASSERT_EQ(offline.exit_code, 0) << offline.err;
  EXPECT_TRUE(same_file(dir / "a.png", dir / "b.png"));
  EXPECT_EQ(server.wait_log([&](const auto& l) { return l.size() > asked_first; }, 0.5).size(),
            asked_first)
      << "--offline sent requests";
  // A restart revalidates every stale tile: 304s, the same picture.
  const RunResult again = run(viewer() + " " + sources + " --cache-dir " + cache +
                                  " --size 256x160 --stats --snapshot " + (dir / "c.png").string(),
                              dir.path());
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_TRUE(same_file(dir / "a.png", dir / "c.png"));
  auto stats = network_stats(again.out);
  EXPECT_GT(stats["revalidated"], 0) << again.out;
  // A long flight with a 1 MB cache: the file stays within it (plus slack).
  std::ofstream(dir / "path.txt") << "0,0,8000000,0,0\n30,20,4000000,0,0\n60,40,2000000,0,0\n"
                                     "90,30,2000000,0,0\n120,10,2000000,0,0\n150,-10,2000000,0,0\n"
                                     "-170,-30,2000000,0,0\n-120,-20,2000000,0,0\n";
  const std::string small = (dir / "small").string();
  const RunResult flight =
      run(viewer() + " " + sources + " --cache-dir " + small + " --http-cache-mb 1 --camera-path " +
              (dir / "path.txt").string() + " --size 256x160 --stats",
          dir.path());
  ASSERT_EQ(flight.exit_code, 0) << flight.err;
  EXPECT_LE(fs::file_size(fs::path(small) / "http-cache.sqlite"), (1u << 20) + (64u << 10));
  server.stop();
  // Availability: every terrain tile asked for is inside the announced ranges
  // (zooms 0..3 here), and none was asked twice in one run with a 404.
  for (const LogEntry& e : server.log()) {
    if (e.path.rfind("/terrain/", 0) != 0) continue;
    EXPECT_NE(e.status, 404) << e.path << ": a tile the source does not announce";
  }
}

// Bad sources get a clear error naming the URL, exit 1.
TEST(ViewerRemoteErrors, UnreachableAndForeignSourcesAreNamed) {
  TempDir dir;
  fs::create_directories(dir / "www");
  std::ofstream(dir / "www" / "p.json") << "{\"type\":\"FeatureCollection\",\"features\":[]}";
  FaultServer server(dir / "www", {}, dir.path());
  ASSERT_GT(server.port(), 0);
  const std::string cache = " --cache-dir " + (dir / "cache").string();
  struct Case {
    std::string url, says;
  };
  for (const Case& c : std::vector<Case>{{server.url("/nothing.json"), "nothing.json"},
                                         {server.url("/p.json"), "p.json"},
                                         {"http://127.0.0.1:1/x.json", "127.0.0.1:1"}}) {
    const RunResult r = snapshot(c.url + cache, dir / "x.png", dir.path());
    EXPECT_EQ(r.exit_code, 1) << c.url << ": " << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "x.png"));
  }
  // A cache folder that cannot be made: exit 1, naming it and what to do.
  const RunResult r = snapshot(server.url("/p.json") + " --cache-dir /proc/no-such-folder",
                               dir / "x.png", dir.path());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("/proc/no-such-folder"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--cache-dir"), std::string::npos) << r.err;
}

}  // namespace
