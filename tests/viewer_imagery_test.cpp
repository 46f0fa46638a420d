// globe-view drapes imagery as a user runs it: a straight-down view of a
// flat terrain under `--shading imagery` reproduces the `gdalwarp` program's
// warp of the sample image onto the view's ground grid, for each pairing of
// terrain and image tilings; bad input gets a clear error or a warning.
#include <gtest/gtest.h>

#include <gdal.h>

#include <cmath>
#include <numbers>
#include <sstream>

#include "raster_fixtures.hpp"
#include "render_fixtures.hpp"
#include "test_paths.hpp"
#include "test_support.hpp"

namespace {

using namespace globe_test;

constexpr double kLon = -34.8722, kLat = -7.9990;  // inside landsat.tif (Olinda)
constexpr double kHeight = 10000;                  // metres above the flat ground
constexpr int kSize = 256;

struct Pairing {
  std::string name, terrain_tiling, image_tiling;
  bool globe = false;  // on the WGS84 ellipsoid (--globe): 10 km up, its 8 km view
                       // bends by 1.3 m, far below a pixel (32 m)
};

void PrintTo(const Pairing& p, std::ostream* os) {
  *os << p.name;
}

class ViewerImagery : public ::testing::TestWithParam<Pairing> {};

// The view's ground grid, from first principles: a straight-down camera at
// height H with a 45-degree vertical field of view sees 2 H tan(22.5 deg)
// metres across kSize pixels, north up, centred below it. In the terrain's
// CRS that is: webmercator, metres stretched by 1/cos(lat); geodetic, degrees
// from the WGS84 radii of curvature; local (UTM), metres.
std::string reference_grid(const std::string& tiling, const fs::path& scratch, std::string& srs) {
  const double px_m = 2 * kHeight * std::tan(22.5 * std::numbers::pi / 180) / kSize;
  const double phi = kLat * std::numbers::pi / 180;
  double cx, cy, px, py;
  if (tiling == "webmercator") {
    srs = "EPSG:3857";
    const double R = 6378137.0;
    cx = R * kLon * std::numbers::pi / 180;
    cy = R * std::atanh(std::sin(phi));
    px = py = px_m / std::cos(phi);
  } else if (tiling == "geodetic") {
    srs = "EPSG:4326";
    const double a = 6378137.0, e2 = 0.00669437999014, s2 = std::sin(phi) * std::sin(phi);
    const double m_lat = a * (1 - e2) / std::pow(1 - e2 * s2, 1.5) * std::numbers::pi / 180;
    const double m_lon = a * std::cos(phi) / std::sqrt(1 - e2 * s2) * std::numbers::pi / 180;
    cx = kLon, cy = kLat, px = px_m / m_lon, py = px_m / m_lat;
  } else {
    srs = "EPSG:32725";  // landsat.tif's own CRS, UTM 25S
    const RunResult r = run("echo '" + std::to_string(kLon) + " " + std::to_string(kLat) +
                                "' | gdaltransform -s_srs EPSG:4326 -t_srs EPSG:32725 -output_xy",
                            scratch);
    std::istringstream(r.out) >> cx >> cy;
    px = py = px_m;
  }
  char te[256];
  std::snprintf(te, sizeof te, "-te %.12g %.12g %.12g %.12g", cx - px * kSize / 2,
                cy - py * kSize / 2, cx + px * kSize / 2, cy + py * kSize / 2);
  return te;
}

TEST_P(ViewerImagery, StraightDownViewMatchesGdalwarp) {
  const Pairing& p = GetParam();
  TempDir dir;
  // A flat terrain (height 0) over the image, in lon/lat.
  const double gt[6] = {-34.93, 0.002, 0, -7.93, 0, -0.002};
  write_dem((dir / "flat.tif").string(), 80, 80, gt, "EPSG:4326", GDT_Float32,
            [](int, int) { return 0.0; });
  const std::string terrain = (dir / "t.mbtiles").string(), image = (dir / "i.mbtiles").string();
  auto must = [&](const std::string& cmd) {
    const RunResult r = run(cmd, dir.path());
    ASSERT_EQ(r.exit_code, 0) << cmd << "\n" << r.err;
  };
  const std::string local_srs = p.terrain_tiling == "local" ? " --t_srs EPSG:32725" : "";
  must(tiler() + " terrain -q " + (dir / "flat.tif").string() + " --tiling " + p.terrain_tiling +
       local_srs + " -o " + terrain);
  must(tiler() + " imagery -q " + sample("landsat.tif").string() + " --bands 3,2,1 --tiling " +
       p.image_tiling + " -o " + image);
  const std::string snap = (dir / "view.png").string();
  char camera[128];
  std::snprintf(camera, sizeof camera, "--camera=%.6f,%.6f,%.1f,0,0", kLon, kLat, kHeight);
  must(viewer() + " " + terrain + " " + image + (p.globe ? " --globe" : "") +
       " --shading imagery --platform osmesa --size " + std::to_string(kSize) + "x" +
       std::to_string(kSize) + " " + camera + " --snapshot " + snap);
  // The reference: gdalwarp of the source image onto the ground grid.
  std::string srs;
  const std::string te = reference_grid(p.terrain_tiling, dir.path(), srs);
  const std::string ref = (dir / "ref.tif").string();
  // (GDAL 3.6's gdalwarp has no -b: the bands are picked by gdal_translate.)
  const std::string bands = (dir / "bands.vrt").string();
  must("gdal_translate -q -of VRT -b 3 -b 2 -b 1 " + sample("landsat.tif").string() + " " + bands);
  must("gdalwarp -q -overwrite -et 0 -r bilinear -dstalpha -t_srs " + srs + " " + te + " -ts " +
       std::to_string(kSize) + " " + std::to_string(kSize) + " " + bands + " " + ref);
  int w = 0, h = 0, rw = 0, rh = 0;
  const std::vector<uint8_t> got = read_rgb(snap, w, h), want = read_rgb(ref, rw, rh);
  ASSERT_EQ(w, kSize);
  ASSERT_EQ(rw, kSize);
  // Pixels the reference covers fully (alpha 255), away from its border.
  gdal_setup();
  GDALDatasetH ds = GDALOpen(ref.c_str(), GA_ReadOnly);
  std::vector<uint8_t> alpha(size_t(kSize) * kSize);
  ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(ds, 4), GF_Read, 0, 0, kSize, kSize, alpha.data(), kSize,
                         kSize, GDT_Byte, 0, 0),
            CE_None);
  GDALClose(ds);
  double se = 0;
  size_t n = 0;
  for (size_t i = 0; i < alpha.size(); ++i) {
    if (alpha[i] != 255) continue;
    for (int c = 0; c < 3; ++c) {
      const double d = double(got[3 * i + c]) - double(want[3 * i + c]);
      se += d * d;
    }
    n += 3;
  }
  ASSERT_GT(n, size_t(kSize) * kSize * 3 / 2) << "the reference covers too little of the view";
  const double psnr = 10 * std::log10(255.0 * 255.0 / (se / double(n)));
  std::printf("%s: PSNR %.2f dB\n", p.name.c_str(), psnr);
  EXPECT_GE(psnr, 30.0) << p.name << ": view " << snap << " vs gdalwarp " << ref;
  if (psnr < 30.0) {
    fs::copy_file(snap,
                  fs::path(globe_test::paths::render_diff_dir()) / ("imagery-" + p.name + ".png"),
                  fs::copy_options::overwrite_existing);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Pairings, ViewerImagery,
    ::testing::Values(Pairing{"webmercator_on_webmercator", "webmercator", "webmercator"},
                      Pairing{"geodetic_on_webmercator", "webmercator", "geodetic"},
                      Pairing{"webmercator_on_local", "local", "webmercator"},
                      Pairing{"webmercator_on_geodetic", "geodetic", "webmercator"},
                      Pairing{"geodetic_on_geodetic", "geodetic", "geodetic"},
                      Pairing{"webmercator_on_geodetic_globe", "geodetic", "webmercator", true},
                      Pairing{"geodetic_on_webmercator_globe", "webmercator", "geodetic", true},
                      Pairing{"webmercator_on_webmercator_globe", "webmercator", "webmercator",
                              true}),
    [](const ::testing::TestParamInfo<Pairing>& i) { return i.param.name; });

// Alone, an image package is draped over a flat base (docs/viewer.md
// "Without terrain"): the frame shows the image, framed by --fit.
TEST(ViewerImageryInput, AnImagePackageAloneIsDrawnOverAFlatBase) {
  TempDir dir;
  const std::string image = (dir / "i.mbtiles").string();
  ASSERT_EQ(
      run(tiler() + " imagery -q " + sample("landsat.tif").string() + " --bands 3,2,1 -o " + image,
          dir.path())
          .exit_code,
      0);
  const std::string png = (dir / "x.png").string();
  const RunResult r = run(viewer() + " " + image + " --platform osmesa --fit --size 160x90 " +
                              "--shading imagery --snapshot " + png,
                          dir.path());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("no terrain given"), std::string::npos) << r.err;
  int w = 0, h = 0;
  const std::vector<uint8_t> rgb = read_rgb(png, w, h);
  Census census;
  // The flat base alone is one grey; the image brings other colours.
  const double coloured = census.fraction(rgb, [](const uint8_t* p) {
    return std::abs(int(p[0]) - int(p[1])) > 6 || std::abs(int(p[1]) - int(p[2])) > 6;
  });
  EXPECT_GT(coloured, 0.3) << "the image is not draped";
}

// Olinda: a DEM and a Landsat scene of the same ground, tiled once per run.
struct Olinda {
  fs::path dir;
  std::string terrain, natural, false_colour;
};

const Olinda& olinda() {
  static const Olinda o = [] {
    Olinda k;
    k.dir = shared_folder("globe-view-imagery", [](const fs::path& dir) {
      auto at = [&](const char* name) { return (dir / name).string(); };
      const std::string landsat = sample("landsat.tif").string();
      return run_all(
          {tiler() + " terrain -q " + sample("olinda.tif").string() + " -o " + at("olinda.mbtiles"),
           tiler() + " imagery -q " + landsat + " --bands 3,2,1 -o " + at("landsat321.mbtiles"),
           tiler() + " imagery -q " + landsat + " --bands 4,3,2 -o " + at("landsat432.mbtiles")},
          dir);
    });
    k.terrain = (k.dir / "olinda.mbtiles").string();
    k.natural = (k.dir / "landsat321.mbtiles").string();
    k.false_colour = (k.dir / "landsat432.mbtiles").string();
    return k;
  }();
  return o;
}

const char* kOlindaOblique = " --size 320x180 --camera=-34.88,-8.07,2500,20,70";

RunResult view(const std::string& args, const fs::path& dir) {
  return run(viewer() + " --platform osmesa " + args, dir);
}

TEST(ViewerImageryRender, ObliqueOverOlindaMatchesExpected) {
  TempDir dir;
  const std::string snap = (dir / "a.png").string();
  const RunResult r =
      view(olinda().terrain + " " + olinda().natural + kOlindaOblique + " --snapshot " + snap,
           dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_image(snap, "olinda_landsat_oblique");
}

// A magic lens that shows the image layers: only inside it, exactly as drawn
// everywhere; outside, the terrain alone, byte for byte.
TEST(ViewerImageryRender, ALensShowsTheImagesOnlyInsideIt) {
  TempDir dir;
  auto shot = [&](const std::string& name, const std::string& packages) {
    const std::string png = (dir / (name + ".png")).string();
    EXPECT_EQ(view(packages + kOlindaOblique + " --snapshot " + png, dir.path()).exit_code, 0);
    int w = 0, h = 0;
    return read_rgb(png, w, h);
  };
  const std::string t = olinda().terrain, i = olinda().natural;
  const auto plain = shot("plain", t), images = shot("images", t + " " + i),
             lens = shot("lens", t + " " + i + " --lens 160,100,50:images");
  EXPECT_GT(expect_lens_frame(plain, images, lens, 320, 180, 160, 100, 50), 5000u);
}

TEST(ViewerImageryRender, TwoBlendedLayersMatchExpected) {
  TempDir dir;
  const std::string snap = (dir / "a.png").string();
  const RunResult r = view(olinda().terrain + " " + olinda().natural + " " + olinda().false_colour +
                               " --image-opacity 1,0.5" + kOlindaOblique + " --snapshot " + snap,
                           dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_image(snap, "olinda_landsat_blended");
}

TEST(ViewerImageryInput, CorruptImageTileWarnsAndShowsTheCoarserImage) {
  TempDir dir;
  const std::string broken = (dir / "broken.mbtiles").string();
  fs::copy_file(olinda().natural, broken);
  // Every tile of the finest zoom becomes 64 random bytes.
  const RunResult s = run("sqlite3 " + broken +
                              " \"UPDATE blobs SET tile_data = randomblob(64) WHERE blob_id IN "
                              "(SELECT blob_id FROM map WHERE zoom_level = "
                              "(SELECT max(zoom_level) FROM map));\"",
                          dir.path());
  ASSERT_EQ(s.exit_code, 0) << s.err;
  const std::string camera = " --size 128x128 --camera=-34.8722,-7.999,1500,0,0";
  const RunResult good = view(olinda().terrain + " " + olinda().natural + camera +
                                  " --shading imagery --snapshot " + (dir / "good.png").string(),
                              dir.path());
  const RunResult bad = view(olinda().terrain + " " + broken + camera +
                                 " --shading imagery --snapshot " + (dir / "bad.png").string(),
                             dir.path());
  const RunResult bare =
      view(olinda().terrain + camera + " --snapshot " + (dir / "bare.png").string(), dir.path());
  ASSERT_EQ(good.exit_code, 0) << good.err;
  ASSERT_EQ(bad.exit_code, 0) << bad.err;
  ASSERT_EQ(bare.exit_code, 0) << bare.err;
  EXPECT_NE(bad.err.find("broken.mbtiles: image tile"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("the image of its finer or coarser tiles is shown there"),
            std::string::npos)
      << bad.err;
  int w, h;
  const auto g = read_rgb((dir / "good.png").string(), w, h);
  const auto b = read_rgb((dir / "bad.png").string(), w, h);
  const auto t = read_rgb((dir / "bare.png").string(), w, h);
  // The coarser image is a blurred copy of the finest: close to it, far
  // from the terrain without imagery.
  const double to_good = psnr(b, g), to_bare = psnr(b, t);
  std::printf("broken finest zoom: PSNR %.1f dB to the intact view, %.1f dB to no imagery\n",
              to_good, to_bare);
  EXPECT_GT(to_good, 22.0);
  EXPECT_GT(to_good, to_bare + 8.0);
  EXPECT_LT(to_good, 60.0) << "the broken tiles were drawn anyway?";
}

TEST(ViewerImageryInput, ImageWithNoOverlapWarnsAndShowsTheTerrain) {
  TempDir dir;
  const std::string far = (dir / "far.mbtiles").string();
  ASSERT_EQ(
      run(tiler() + " imagery -q " + sample("cbers20.tif").string() + " -o " + far, dir.path())
          .exit_code,
      0);
  const std::string camera = " --size 128x72" + std::string(" --camera=-34.88,-8.07,2500,20,70");
  const RunResult with =
      view(olinda().terrain + " " + far + camera + " --snapshot " + (dir / "with.png").string(),
           dir.path());
  const RunResult bare =
      view(olinda().terrain + camera + " --snapshot " + (dir / "bare.png").string(), dir.path());
  ASSERT_EQ(with.exit_code, 0) << with.err;
  ASSERT_EQ(bare.exit_code, 0) << bare.err;
  EXPECT_NE(with.err.find("far.mbtiles: the image"), std::string::npos) << with.err;
  EXPECT_NE(with.err.find("does not overlap the terrain"), std::string::npos) << with.err;
  int w, h;
  EXPECT_GT(psnr(read_rgb((dir / "with.png").string(), w, h),
                 read_rgb((dir / "bare.png").string(), w, h)),
            50.0);
}

// The window as a user drives it, under a virtual X server: V hides the
// image layer, V shows it again and five presses of [ take its opacity to
// 0.5. Each screenshot (P) must match the headless view of the same state.
TEST(ViewerImageryWindow, KeysHideAndFadeTheImageLayer) {
  TempDir dir;
  const std::string packages = olinda().terrain + " " + olinda().natural;
  const RunResult w =
      run("xvfb-run -a -s '-screen 0 640x480x24' " + globe_test::paths::test_data_dir() +
              "/window/drive_keys.sh " + dir.path().string() +
              " ';v;v bracketleft bracketleft bracketleft bracketleft bracketleft' " + viewer() +
              " --platform glfw " + packages + kOlindaOblique,
          dir.path());
  ASSERT_EQ(w.exit_code, 0) << w.err << read_file(dir / "viewer.stderr");
  struct Expect {
    std::string shot, args;
  };
  const Expect expect[] = {{"globe-view-1.png", packages},
                           {"globe-view-2.png", olinda().terrain},
                           {"globe-view-3.png", packages + " --image-opacity 0.5"}};
  std::vector<std::vector<uint8_t>> headless;
  for (const Expect& e : expect) {
    const std::string snap = (dir / ("headless-" + e.shot)).string();
    const RunResult r = view(e.args + kOlindaOblique + " --snapshot " + snap, dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    int w1, h1, w2, h2;
    const auto shot = read_rgb((dir / e.shot).string(), w1, h1);
    const auto want = read_rgb(snap, w2, h2);
    ASSERT_EQ(shot.size(), want.size()) << e.shot;
    std::printf("%s: PSNR %.1f dB to the headless view\n", e.shot.c_str(), psnr(shot, want));
    EXPECT_GT(psnr(shot, want), 35.0) << e.shot << " vs the headless view with " << e.args;
    headless.push_back(want);
  }
  // The three states differ from each other, so the checks above can fail.
  EXPECT_LT(psnr(headless[0], headless[1]), 25.0);
  EXPECT_LT(psnr(headless[0], headless[2]), 30.0);
}

// --stats reports the imagery pass; a settled view takes one pass a frame
// (a geodetic global terrain under a webmercator image, near the sheet's
// eastern edge, as bench/imagery_view.sh measures).
TEST(ViewerImageryStats, StatsReportTheImagePass) {
  TempDir dir;
  const std::string t = (dir / "etopo.mbtiles").string(), i = (dir / "bm.mbtiles").string();
  ASSERT_EQ(
      run(tiler() + " terrain -q --tiling geodetic " + sample("etopo20.tif").string() + " -o " + t,
          dir.path())
          .exit_code,
      0);
  ASSERT_EQ(
      run(tiler() + " imagery -q --max-zoom 2 " + sample("bluemarble.tif").string() + " -o " + i,
          dir.path())
          .exit_code,
      0);
  const RunResult r = view(
      t + " " + i + " --stats --frames 2 --size 320x180 --camera=-70,-20,800000,90,70", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"image_layers\": 1,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"image_passes\": 1,"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("\"image_tiles_resident\": 0,"), std::string::npos) << r.out;
}

// --globe refuses what it cannot draw, naming it: a local CRS package, and
// the flat-frame baseline of lines (--lines geometry).
TEST(ViewerImageryInput, GlobeRefusesLocalPackagesAndGeometryLines) {
  TempDir dir;
  const std::string local = (dir / "local.mbtiles").string();
  ASSERT_EQ(
      run(tiler() + " terrain -q --tiling local " + sample("olinda.tif").string() + " -o " + local,
          dir.path())
          .exit_code,
      0);
  const std::string snap = " --snapshot " + (dir / "x.png").string();
  const RunResult a = view(local + " --globe" + snap, dir.path());
  EXPECT_EQ(a.exit_code, 2) << a.err;
  EXPECT_NE(a.err.find("local CRS"), std::string::npos) << a.err;
  const std::string lines = (dir / "lines.mbtiles").string();
  ASSERT_EQ(run("gdal_contour -q -i 20 -a elev " + sample("olinda.tif").string() + " " +
                    (dir / "c.shp").string() + " && " + vectorize() + " lines -q " +
                    (dir / "c.shp").string() + " -o " + lines,
                dir.path())
                .exit_code,
            0);
  const RunResult b =
      view(olinda().terrain + " " + lines + " --globe --lines geometry" + snap, dir.path());
  EXPECT_EQ(b.exit_code, 2) << b.err;
  EXPECT_NE(b.err.find("--lines geometry"), std::string::npos) << b.err;
  EXPECT_FALSE(fs::exists(dir / "x.png"));
}

}  // namespace
