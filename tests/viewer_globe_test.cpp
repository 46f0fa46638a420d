// globe-view --globe as a user runs it: a global package from orbit (the
// whole disc with --fit), close oblique views, the polar caps of a
// webmercator package, against expected PNGs and checks from first
// principles (the disc's size from the ellipsoid and the camera).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <regex>

#include "render_fixtures.hpp"
#include "test_paths.hpp"
#include "test_support.hpp"
#include "tileformat/json.hpp"

namespace {

using namespace globe_test;

struct Globes {
  fs::path dir;
  std::string geodetic, mercator, bluemarble, contours;
};

const Globes& globes() {
  static const Globes g = [] {
    Globes k;
    k.dir = shared_folder("globe-view-globe", [](const fs::path& dir) {
      auto at = [&](const char* name) { return (dir / name).string(); };
      const std::string etopo = sample("etopo20.tif").string();
      return run_all({tiler() + " terrain -q --tiling geodetic " + etopo + " -o " +
                          at("etopo_geodetic.mbtiles"),
                      tiler() + " terrain -q --tiling webmercator " + etopo + " -o " +
                          at("etopo_webmercator.mbtiles"),
                      // Blue Marble (webmercator, zooms 0-3) and 1000 m contours of
                      // etopo20 (geodetic, as the terrain).
                      tiler() + " imagery -q --max-zoom 3 " + sample("bluemarble.tif").string() +
                          " -o " + at("bluemarble.mbtiles"),
                      "gdal_contour -q -i 1000 -a elev " + etopo + " " + at("c1000.shp"),
                      vectorize() + " lines -q --tiling geodetic " + at("c1000.shp") + " -o " +
                          at("contours.mbtiles") + " --style 'c1000:color=#ffd92f,width=1.5px'"},
                     dir);
    });
    k.geodetic = (k.dir / "etopo_geodetic.mbtiles").string();
    k.mercator = (k.dir / "etopo_webmercator.mbtiles").string();
    k.bluemarble = (k.dir / "bluemarble.mbtiles").string();
    k.contours = (k.dir / "contours.mbtiles").string();
    return k;
  }();
  return g;
}

RunResult view(const std::string& args, const fs::path& dir) {
  return run(viewer() + " --platform osmesa --globe " + args, dir);
}

bool is_sky(const std::vector<uint8_t>& rgb, size_t i) {
  return globe_test::is_sky(&rgb[3 * i]);
}

// A package with broken tiles is drawn around them (issue 55: the three
// coarsest tiles of a global package made unreadable blanked the globe,
// exit 6). Each zoom's tiles in turn (etopo20 geodetic has zooms 0..2, so
// the top three and the finest), and the three coarsest alone, become
// random bytes: from orbit and over the Alps the frame shows as much ground
// as the intact package's (>= 0.99 x its ground_fraction), exits 0, and
// names each broken tile it met once. (Samples nest across zooms, so a
// tile remade from its children is exact; from its parent, interpolated.)
TEST(ViewerGlobe, BrokenTilesAreDrawnFromTheirChildrenOrParent) {
  TempDir dir;
  const std::map<std::string, std::string> cameras = {
      {"orbit", "--fit"}, {"alps", "--camera=8,40,700000,0,60 --exaggeration 20"}};
  auto ground = [&](const std::string& pkg, const std::string& camera, std::string* err) {
    const RunResult r = view(pkg + " " + camera + " --size 160x90 --stats --frames 1", dir.path());
    EXPECT_EQ(r.exit_code, 0) << pkg << " " << camera << "\n" << r.err;
    if (err) *err = r.err;
    const auto stats = tileformat::JsonValue::parse(r.out);
    return stats.find("ground_fraction")->number();
  };
  std::map<std::string, double> intact;
  for (const auto& [name, camera] : cameras)
    intact[name] = ground(globes().geodetic, camera, nullptr);
  const std::vector<std::pair<std::string, std::string>> breaks = {
      {"the three coarsest tiles",
       "blob_id IN (SELECT blob_id FROM map ORDER BY zoom_level, tile_column, tile_row LIMIT 3)"},
      {"zoom 0", "blob_id IN (SELECT blob_id FROM map WHERE zoom_level = 0)"},
      {"zoom 1", "blob_id IN (SELECT blob_id FROM map WHERE zoom_level = 1)"},
      {"zoom 2 (the finest)", "blob_id IN (SELECT blob_id FROM map WHERE zoom_level = 2)"}};
  for (const auto& [what, where] : breaks) {
    const std::string pkg = (dir / "broken.mbtiles").string();
    fs::remove(pkg);
    fs::copy_file(globes().geodetic, pkg);
    const RunResult s = run("sqlite3 " + pkg + " \"UPDATE blobs SET tile_data = randomblob(500) " +
                                "WHERE " + where + ";\"",
                            dir.path());
    ASSERT_EQ(s.exit_code, 0) << s.err;
    size_t named_here = 0;
    for (const auto& [name, camera] : cameras) {
      std::string err;
      const double g = ground(pkg, camera, &err);
      EXPECT_GE(g, 0.99 * intact[name])
          << what << ", " << name << ": " << g << " against " << intact[name] << "\n"
          << err;
      std::map<std::string, int> named;
      const std::regex tile("tile ([0-9]+/[0-9]+/[0-9]+): ");
      for (auto m = std::sregex_iterator(err.begin(), err.end(), tile); m != std::sregex_iterator();
           ++m)
        ++named[(*m)[1]];
      named_here += named.size();
      for (const auto& [id, times] : named)
        EXPECT_EQ(times, 1) << what << ", " << name << ": tile " << id << " named " << times
                            << " times\n"
                            << err;
    }
    EXPECT_GT(named_here, 0u) << what << ": no broken tile named";
  }
}

// Image and line tiles too (issue 55): the two coarsest zooms of Blue
// Marble and of the contours broken, from orbit, where the view wants those
// zooms: the image is drawn from their children (as the intact frame, within
// 40 dB PSNR; the terrain alone is below 15 dB), the lines from their finer
// tiles kept a pixel wide (at least 70 % of the intact frame's line pixels).
// Before, both layers vanished (nothing coarser to fall back to).
TEST(ViewerGlobe, BrokenImageAndLineTilesAreDrawnFromFinerTiles) {
  TempDir dir;
  auto broken_copy = [&](const std::string& from, const std::string& name) {
    const std::string pkg = (dir / name).string();
    fs::copy_file(from, pkg);
    const RunResult s = run("sqlite3 " + pkg +
                                " \"UPDATE blobs SET tile_data = randomblob(300) WHERE blob_id IN "
                                "(SELECT blob_id FROM map WHERE zoom_level <= 1);\"",
                            dir.path());
    EXPECT_EQ(s.exit_code, 0) << s.err;
    return pkg;
  };
  const std::string images = broken_copy(globes().bluemarble, "images.mbtiles"),
                    lines = broken_copy(globes().contours, "lines.mbtiles");
  auto shot = [&](const std::string& name, const std::string& layers, std::string* err = nullptr) {
    const std::string png = (dir / (name + ".png")).string();
    const RunResult r = view(
        globes().geodetic + " " + layers + " --fit --size 160x90 --snapshot " + png, dir.path());
    EXPECT_EQ(r.exit_code, 0) << name << "\n" << r.err;
    if (err) *err = r.err;
    int w = 0, h = 0;
    return read_rgb(png, w, h);
  };
  std::string image_err, line_err;
  const auto bare = shot("bare", ""), image_intact = shot("image", globes().bluemarble),
             image_broken = shot("image-broken", images, &image_err);
  EXPECT_NE(image_err.find("images.mbtiles: image tile 0/0/0"), std::string::npos) << image_err;
  EXPECT_GE(psnr(image_broken, image_intact), 40) << image_err;
  EXPECT_LT(psnr(bare, image_intact), 15);
  auto yellow = [](const std::vector<uint8_t>& rgb) {  // the contours' #ffd92f
    size_t n = 0;
    for (size_t i = 0; i + 2 < rgb.size(); i += 3)
      n += rgb[i] > 200 && rgb[i + 1] > 170 && rgb[i + 2] < 120;
    return n;
  };
  const auto line_intact = shot("lines", globes().contours),
             line_broken = shot("lines-broken", lines, &line_err);
  EXPECT_NE(line_err.find("lines.mbtiles: line tile 0/0/0"), std::string::npos) << line_err;
  EXPECT_GT(yellow(line_intact), 500u);
  EXPECT_GE(yellow(line_broken), yellow(line_intact) * 7 / 10) << line_err;
}

TEST(ViewerGlobe, FitShowsTheWholeDiscFromOrbit) {
  TempDir dir;
  const std::string snap = (dir / "a.png").string();
  const RunResult r =
      view(globes().geodetic + " --fit --exaggeration 30 --size 320x180 --snapshot " + snap +
               " --stats --frames 1",
           dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int w, h;
  const auto rgb = read_rgb(snap, w, h);
  // The border is sky; the disc's vertical extent follows from the eye's
  // distance D = kA * 1.05 / sin(fov / 2) (what --fit promises: the
  // equatorial radius plus 5% fills the half-height): the disc subtends
  // asin(kA / D) of the 22.5-degree half field of view.
  for (int x = 0; x < w; ++x) {
    EXPECT_TRUE(is_sky(rgb, size_t(x))) << "top row, x " << x;
    EXPECT_TRUE(is_sky(rgb, size_t(h - 1) * w + x)) << "bottom row, x " << x;
  }
  int top = -1, bottom = -1;
  for (int y = 0; y < h; ++y)
    if (!is_sky(rgb, size_t(y) * w + w / 2)) {
      if (top < 0) top = y;
      bottom = y;
    }
  const double half = 22.5 * std::numbers::pi / 180;
  const double disc = std::asin(std::sin(half) / 1.05);  // angular radius of the equator
  // (the polar radius is 0.3% smaller; the view is straight down at 0,0)
  const double want = std::tan(disc) / std::tan(half) * h;
  EXPECT_NEAR(bottom - top + 1, want, 4.0) << "top " << top << " bottom " << bottom;
  expect_image(snap, "globe_etopo_orbit");
}

TEST(ViewerGlobe, ObliqueViewOverTheAlpsMatchesExpected) {
  TempDir dir;
  const std::string snap = (dir / "a.png").string();
  const RunResult r = view(globes().geodetic + " --camera=8,40,700000,0,60 --exaggeration 20" +
                               " --size 320x180 --snapshot " + snap,
                           dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_image(snap, "globe_etopo_alps");
}

TEST(ViewerGlobe, WebMercatorPolesAreCapsNotHoles) {
  TempDir dir;
  for (const char* cam : {"0,90,3000000,0,0", "0,-90,3000000,0,0"}) {
    const std::string snap = (dir / "a.png").string();
    const RunResult r = view(
        globes().mercator + " --camera=" + cam + " --size 160x120 --snapshot " + snap, dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    int w, h;
    const auto rgb = read_rgb(snap, w, h);
    // Straight down on the pole: beyond 85.05 degrees there are no tiles,
    // and the cap must cover it (the centre 20 x 20 pixels, 4.95 degrees of
    // latitude span about 30 px here).
    for (int y = h / 2 - 10; y < h / 2 + 10; ++y)
      for (int x = w / 2 - 10; x < w / 2 + 10; ++x)
        ASSERT_FALSE(is_sky(rgb, size_t(y) * w + x)) << cam << ": sky at " << x << "," << y;
    if (cam[2] == '9') expect_image(snap, "globe_webmercator_north_cap");
  }
}

TEST(ViewerGlobe, ImageryFromOrbitMatchesExpected) {
  TempDir dir;
  const std::string snap = (dir / "a.png").string();
  const RunResult r = view(
      globes().geodetic + " " + globes().bluemarble + " --fit --size 320x180 --snapshot " + snap,
      dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_image(snap, "globe_bluemarble_orbit");
}

// Over the antimeridian, where ground points, image tiles and line tiles
// all wrap: Bering Sea from 1,500 km, looking east.
TEST(ViewerGlobe, LinesOverImageryAcrossTheAntimeridianMatchExpected) {
  TempDir dir;
  const std::string snap = (dir / "a.png").string();
  const RunResult r = view(globes().geodetic + " " + globes().bluemarble + " " + globes().contours +
                               " --camera=179.5,60,1500000,90,50 --size 320x180 --snapshot " + snap,
                           dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int w, h;
  const auto rgb = read_rgb(snap, w, h);
  // East of the antimeridian (the right half) is imagery and lines too: no
  // plain hillshade grey among the ground pixels there.
  size_t grey = 0, ground = 0;
  for (int y = h / 2; y < h; ++y)
    for (int x = w / 2; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      if (is_sky(rgb, i)) continue;
      ++ground;
      const int r8 = rgb[3 * i], g8 = rgb[3 * i + 1], b8 = rgb[3 * i + 2];
      if (std::abs(r8 - g8) < 6 && std::abs(g8 - b8) < 6 && r8 > 150) ++grey;
    }
  EXPECT_GT(ground, size_t(w * h / 8));
  EXPECT_LT(grey, ground / 50) << "undraped ground east of the antimeridian";
  expect_image(snap, "globe_lines_over_imagery_antimeridian");
}

// The globe is the default for a package spanning more than 30 degrees in
// a global tiling; --flat keeps the map frame; --lines geometry (flat only)
// picks the flat frame by default too.
TEST(ViewerGlobe, GlobeIsTheDefaultForWidePackages) {
  TempDir dir;
  auto surface = [&](const std::string& args) {
    const RunResult r = run(
        viewer() + " --platform osmesa " + args + " --stats --frames 1 --size 64x48", dir.path());
    EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
    const size_t at = r.out.find("\"surface\": \"");
    return at == std::string::npos ? std::string("?") : r.out.substr(at + 12, 5);
  };
  EXPECT_EQ(surface(globes().geodetic), "globe");
  EXPECT_EQ(surface(globes().mercator), "globe");
  EXPECT_EQ(surface(globes().geodetic + " --flat"), "flat\"");
  EXPECT_EQ(surface(globes().geodetic + " " + globes().contours + " --lines geometry"), "flat\"");
}

// The window on the globe, driven by keys under a virtual X server: the
// whole disc first (sky in the corners), then eight presses of W zoom in
// until the globe fills the window, and the arrows pan over it.
TEST(ViewerGlobe, WindowZoomsOntoTheGlobe) {
  TempDir dir;
  const RunResult w =
      run("xvfb-run -a -s '-screen 0 640x480x24' " + globe_test::paths::test_data_dir() +
              "/window/drive_keys.sh " + dir.path().string() + " ';w w w w w w w w;Left Left Up' " +
              viewer() + " --platform glfw --size 320x180 " + globes().geodetic + " " +
              globes().bluemarble,
          dir.path());
  ASSERT_EQ(w.exit_code, 0) << w.err << read_file(dir / "viewer.stderr");
  int width, height;
  const auto first = read_rgb((dir / "globe-view-1.png").string(), width, height);
  const auto zoomed = read_rgb((dir / "globe-view-2.png").string(), width, height);
  const auto panned = read_rgb((dir / "globe-view-3.png").string(), width, height);
  EXPECT_TRUE(is_sky(first, 0)) << "the whole disc, sky in the corner";
  size_t sky = 0;
  for (size_t i = 0; i < size_t(width) * height; ++i)
    sky += is_sky(zoomed, i);
  EXPECT_EQ(sky, 0u) << "zoomed in, the globe fills the window";
  EXPECT_NE(zoomed, panned) << "the arrows moved the view";
}

}  // namespace
