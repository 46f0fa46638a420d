// Global, polar and antimeridian DEMs (docs/terrain.md "Warping"): the
// extents global users tile. Fixtures are made here from the etopo20 sample
// (NOAA 20' relief, lon 0..360, fetched by samples/fetch.sh) with GDAL's API
// or the gdalwarp program; each is tiled in both global schemes, and the
// finest zoom (`extract`) is compared with the gdalwarp program (-et 0,
// bilinear) onto the same grid. A mosaic reference is what a user would
// run: gdalwarp with the +-360 shifted copy first and the file itself last.
#include <gtest/gtest.h>

#include <cpl_string.h>
#include <gdal.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "raster_fixtures.hpp"
#include "test_support.hpp"

using namespace globe_test;

namespace {

constexpr double kStep = 0.01;        // the packages' height step (float DEMs)
constexpr double kTolerance = 0.001;  // see real_dem_test.cpp

// etopo20 as read: 1081 x 540 samples, the last column repeating the first.
struct Grid {
  int width = 0, height = 0;
  std::array<double, 6> gt{};
  std::vector<float> data;
  float at(int x, int y) const { return data[size_t(y) * width + x]; }
};

Grid read_etopo() {
  gdal_setup();
  Grid g;
  GDALDatasetH ds = GDALOpen(sample("etopo20.tif").c_str(), GA_ReadOnly);
  if (!ds) return g;
  g.width = GDALGetRasterXSize(ds);
  g.height = GDALGetRasterYSize(ds);
  GDALGetGeoTransform(ds, g.gt.data());
  g.data.resize(size_t(g.width) * g.height);
  if (GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Read, 0, 0, g.width, g.height, g.data.data(),
                   g.width, g.height, GDT_Float32, 0, 0) != CE_None)
    g.data.clear();
  GDALClose(ds);
  return g;
}

void write_grid(const fs::path& path, int w, int h, const std::array<double, 6>& gt,
                const std::function<double(int, int)>& at) {
  write_dem(path.string(), w, h, gt.data(), "EPSG:4326", GDT_Float32, at);
}

// The fixtures, made once per test binary run in one folder.
class Fixtures {
 public:
  static const Fixtures& get() {
    static Fixtures f;
    return f;
  }
  fs::path dir() const { return dir_; }
  fs::path operator/(const std::string& name) const { return dir_ / name; }

 private:
  Fixtures() : dir_(run_scratch_dir("globe-global-dem")) {
    const Grid e = read_etopo();
    if (e.data.empty()) {
      ADD_FAILURE() << "cannot read etopo20.tif";
      return;
    }
    const double d = 1.0 / 3;
    // etopo20's column 480 is the first east of the antimeridian: rolled, the
    // 1080 distinct columns run west to east from there.
    auto rolled = [&](int x, int y) { return e.at((x + 480) % 1080, std::min(y, e.height - 1)); };
    // Grid-registered, as ETOPO/GEBCO grids are: samples on -180..180 and
    // 90..-90 inclusive, pixel areas half a pixel past both.
    write_grid(dir_ / "global_grid.tif", 1081, 541, {-180 - d / 2, d, 0, 90 + d / 2, 0, -d},
               rolled);
    // Cell-registered with the exact extent -180..180, -90..90.
    write_grid(dir_ / "global_exact.tif", 1080, 540, {-180, d, 0, 90, 0, -d}, rolled);
    // All longitudes south of 60 S (grid-registered, to the pole and past it).
    write_grid(dir_ / "south_strip.tif", 1081, 92, {-180 - d / 2, d, 0, -60 + d / 2, 0, -d},
               [&](int x, int y) { return rolled(x, 450 + y); });
    // 160 E .. 200 E (0..360 longitudes), 60 N .. 30 S: across the antimeridian.
    auto gt = e.gt;
    gt[0] += 420 * gt[1];
    gt[3] += 90 * gt[5];
    write_grid(dir_ / "antimeridian.tif", 120, 270, gt,
               [&](int x, int y) { return e.at(420 + x, 90 + y); });
    // The 0..360 original shifted by -360 degrees: the copy a user mosaics
    // under it to cover the western hemisphere.
    {
      GDALDatasetH in = GDALOpen(sample("etopo20.tif").c_str(), GA_ReadOnly);
      const std::string vrt = (dir_ / "etopo20_west.vrt").string();
      GDALDatasetH copy = GDALCreateCopy(GDALGetDriverByName("VRT"), vrt.c_str(), in, FALSE,
                                         nullptr, nullptr, nullptr);
      auto west = e.gt;
      west[0] -= 360;
      GDALSetGeoTransform(copy, west.data());
      GDALClose(copy);
      GDALClose(in);
    }
    // Antarctica in polar stereographic (EPSG:3031), covering the pole: a
    // projected DEM whose lon/lat extent is every longitude.
    const RunResult r =
        run("gdalwarp -q -overwrite -t_srs EPSG:3031 -te -3000000 -3000000 3000000 "
            "3000000 -tr 25000 25000 -r bilinear " +
                (dir_ / "global_exact.tif").string() + " " + (dir_ / "polar_3031.tif").string(),
            dir_);
    EXPECT_EQ(r.exit_code, 0) << r.err;
  }
  fs::path dir_;
};

struct GlobalCase {
  std::string name, file, options;
  std::vector<std::string> reference_under;  // drawn before `file` in the reference mosaic
  std::string reference_options;             // more gdalwarp options
  bool leaves_out = false;                   // data past webmercator's +-85.0511
  // The grid's pixel edges lie on +-180: within half a pixel of it gdalwarp
  // clamps to the edge column (it has no neighbour across), where the grid's
  // own wrap gives one; there the reference is a brute force written here.
  bool edges_on_antimeridian = false;
};

// global_exact.tif's surface at (lon, lat): bilinear between its pixel
// centres, longitudes wrapped (the brute force of the antimeridian strip).
double exact_extent_bilinear(const Grid& e, double lon, double lat) {
  const double d = 1.0 / 3;
  double u = (lon + 180) / d - 0.5;
  u -= std::floor(u / 1080) * 1080;
  const double v = std::clamp((90 - lat) / d - 0.5, 0.0, 539.0);
  const int i = int(std::floor(u)), j = std::min(int(std::floor(v)), 538);
  const double a = u - i, b = v - j;
  auto at = [&](int x, int y) { return double(e.at(((x % 1080) + 480) % 1080, y)); };
  return (1 - b) * ((1 - a) * at(i, j) + a * at(i + 1, j)) +
         b * ((1 - a) * at(i, j + 1) + a * at(i + 1, j + 1));
}

class GlobalDem : public ::testing::TestWithParam<GlobalCase> {};

[[maybe_unused]] void PrintTo(const GlobalCase& c, std::ostream* os) {
  *os << c.name;
}

std::string meta(const std::string& info, const std::string& key) {
  const auto pos = info.find("  " + key + " ");
  if (pos == std::string::npos) return "";
  const auto start = info.find_first_not_of(' ', pos + key.size() + 2);
  return info.substr(start, info.find('\n', start) - start);
}

TEST_P(GlobalDem, FinestZoomMatchesGdalwarp) {
  const GlobalCase& c = GetParam();
  const Fixtures& fx = Fixtures::get();
  TempDir dir;
  const std::string src = (fx / c.file).string();
  const std::string pkg = (dir / "out.mbtiles").string();
  const RunResult r = run(tiler() + " terrain " + src + " " + c.options + " -o " + pkg, dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const RunResult v = run(tiler() + " validate " + pkg, dir.path());
  EXPECT_EQ(v.exit_code, 0) << v.out << v.err;

  const RunResult info = run(tiler() + " info " + pkg, dir.path());
  ASSERT_EQ(info.exit_code, 0);
  // Metadata bounds inside the tiling's range; what webmercator cannot hold
  // is said, in the build's notes and in `info`.
  double b[4] = {0, 0, 0, 0};
  ASSERT_EQ(
      std::sscanf(meta(info.out, "bounds").c_str(), "%lf,%lf,%lf,%lf", &b[0], &b[1], &b[2], &b[3]),
      4)
      << info.out;
  const bool webmercator = c.options.find("geodetic") == std::string::npos;
  const double lat = webmercator ? 85.051128779806589 : 90.0;
  EXPECT_TRUE(b[0] >= -180 && b[2] <= 180 && b[1] >= -lat && b[3] <= lat)
      << meta(info.out, "bounds");
  if (c.leaves_out) {
    EXPECT_NE(info.out.find("left out: latitudes"), std::string::npos) << info.out;
    EXPECT_NE(r.err.find("left out: latitudes"), std::string::npos) << r.err;
  } else {
    EXPECT_EQ(info.out.find("left out:"), std::string::npos) << info.out;
  }

  const int z = std::stoi(meta(info.out, "maxzoom"));
  const std::string ours_path = (dir / "ours.tif").string();
  const RunResult e =
      run(tiler() + " extract " + pkg + " --zoom " + std::to_string(z) + " -o " + ours_path,
          dir.path());
  ASSERT_EQ(e.exit_code, 0) << e.err;
  const Raster ours = read_raster(ours_path);
  std::vector<std::string> sources;
  for (const auto& s : c.reference_under)
    sources.push_back((fx / s).string());
  sources.push_back(src);
  Raster ref = gdalwarp_reference(sources, ours, "bilinear", dir.path(), c.reference_options);
  ASSERT_EQ(ref.data.size(), ours.data.size());
  size_t brute = 0;
  if (c.edges_on_antimeridian) {
    const Grid e = read_etopo();
    const double strip = 1.0 / 6;  // half a pixel
    for (int y = 0; y < ours.height; ++y)
      for (int x = 0; x < ours.width; ++x) {
        double lon = ours.gt[0] + (x + 0.5) * ours.gt[1], lat = ours.gt[3] + (y + 0.5) * ours.gt[5];
        if (webmercator) {
          lon = lon / 6378137.0 * 180 / M_PI;
          lat = std::atan(std::sinh(lat / 6378137.0)) * 180 / M_PI;
        }
        if (std::fabs(lon) < 180 - strip || std::isnan(ref.data[size_t(y) * ours.width + x]))
          continue;
        ref.data[size_t(y) * ours.width + x] = exact_extent_bilinear(e, lon, lat);
        ++brute;
      }
    EXPECT_GT(brute, 0u);
  }
  const HeightComparison cmp = compare_heights(ours, ref);
  std::printf(
      "%s: zoom %d, %zu samples compared (%zu against the brute force), p99.9 |diff| %.4f m, max "
      "%.4f m, only ours %zu, only gdalwarp %zu\n",
      c.name.c_str(), z, cmp.compared, brute, cmp.p999, cmp.max_diff, cmp.only_ours,
      cmp.only_reference);
  EXPECT_LE(cmp.p999, kStep / 2 * (1 + 1e-6));
  EXPECT_LE(cmp.max_diff, kStep / 2 * (1 + 1e-6) + kTolerance);
  // Every sample gdalwarp has, we have too.
  EXPECT_EQ(cmp.only_reference, 0u);
  EXPECT_GT(cmp.compared, ours.data.size() / 20);
}

// Polar stereographic rows and columns turn against the Mercator grid, so
// gdalwarp's kernel scale (the ratio of each warped chunk's destination and
// source window sizes) says "downsampling" where every pixel is upsampled,
// and widens its kernel. XSCALE/YSCALE=1 give it the true local scale (the
// finest zoom upsamples everywhere); in geodetic its own estimate is right.
const char* kTrueScale = "-wo XSCALE=1 -wo YSCALE=1";

INSTANTIATE_TEST_SUITE_P(
    Etopo20, GlobalDem,
    ::testing::Values(
        GlobalCase{
            "grid_registered_geodetic", "global_grid.tif", "--tiling geodetic", {}, "", false},
        GlobalCase{"grid_registered_webmercator", "global_grid.tif", "", {}, "", true},
        GlobalCase{
            "exact_extent_geodetic", "global_exact.tif", "--tiling geodetic", {}, "", false, true},
        GlobalCase{"exact_extent_webmercator", "global_exact.tif", "", {}, "", true, true},
        GlobalCase{"lon_0_360_geodetic",
                   (samples() / "etopo20.tif").string(),
                   "--tiling geodetic",
                   {"etopo20_west.vrt"},
                   "",
                   false},
        GlobalCase{"lon_0_360_webmercator",
                   (samples() / "etopo20.tif").string(),
                   "",
                   {"etopo20_west.vrt"},
                   "",
                   true},
        GlobalCase{"antimeridian_geodetic", "antimeridian.tif", "--tiling geodetic", {}, "", false},
        GlobalCase{"antimeridian_webmercator", "antimeridian.tif", "", {}, "", false},
        GlobalCase{
            "south_pole_strip_geodetic", "south_strip.tif", "--tiling geodetic", {}, "", false},
        GlobalCase{
            "polar_stereographic_geodetic", "polar_3031.tif", "--tiling geodetic", {}, "", false},
        GlobalCase{"polar_stereographic_webmercator", "polar_3031.tif", "", {}, kTrueScale, true}),
    [](const auto& info) { return info.param.name; });

}  // namespace

namespace {

// GDAL's warnings while opening `path` as a raster.
std::vector<std::string> gdal_open_warnings(const std::string& path) {
  gdal_setup();
  static thread_local std::vector<std::string>* sink = nullptr;
  std::vector<std::string> warnings;
  sink = &warnings;
  CPLPushErrorHandler([](CPLErr level, CPLErrorNum, const char* msg) {
    if (level == CE_Warning && sink) sink->push_back(msg);
  });
  GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
  if (!ds) warnings.push_back("GDAL cannot open it");
  if (ds) GDALClose(ds);
  CPLPopErrorHandler();
  sink = nullptr;
  return warnings;
}

std::array<double, 4> bounds_of(const std::string& pkg, const fs::path& dir) {
  const RunResult r =
      run("sqlite3 " + pkg + " \"select value from metadata where name='bounds'\"", dir);
  std::array<double, 4> b{};
  EXPECT_EQ(std::sscanf(r.out.c_str(), "%lf,%lf,%lf,%lf", &b[0], &b[1], &b[2], &b[3]), 4) << r.out;
  return b;
}

}  // namespace

// Global packages of every kind carry `bounds` that readers accept: inside
// -180..180 and webmercator's +-85.0511 (once -180.00000000000003, which GDAL
// ignored with a warning), and GDAL opens the image package without warning.
TEST(GlobalPackages, BoundsAreValidForEveryKind) {
  TempDir dir;
  const auto pkg = [&](const std::string& n) { return (dir / n).string(); };
  ASSERT_EQ(run(tiler() + " terrain -q " + (Fixtures::get() / "global_grid.tif").string() +
                    " --max-zoom 2 -o " + pkg("terrain.mbtiles"),
                dir.path())
                .exit_code,
            0);
  ASSERT_EQ(run(tiler() + " imagery -q " + sample("bluemarble.tif").string() + " --max-zoom 2 -o " +
                    pkg("image.mbtiles"),
                dir.path())
                .exit_code,
            0);
  ASSERT_EQ(run(vectorize() + " lines -q " + sample("ne_admin1.shp").string() +
                    " --max-zoom 2 -o " + pkg("lines.mbtiles"),
                dir.path())
                .exit_code,
            0);
  for (const std::string name : {"terrain.mbtiles", "image.mbtiles", "lines.mbtiles"}) {
    const auto b = bounds_of(pkg(name), dir.path());
    EXPECT_TRUE(b[0] >= -180 && b[2] <= 180 && b[0] < b[2]) << name;
    EXPECT_TRUE(b[1] >= -85.051128779806589 && b[3] <= 85.051128779806589 && b[1] < b[3]) << name;
  }
  // Whole-world image bounds are the tiling's limits, exactly.
  const auto b = bounds_of(pkg("image.mbtiles"), dir.path());
  EXPECT_EQ(b[0], -180.0);
  EXPECT_EQ(b[2], 180.0);
  const auto warnings = gdal_open_warnings(pkg("image.mbtiles"));
  EXPECT_TRUE(warnings.empty()) << warnings.front();
}
