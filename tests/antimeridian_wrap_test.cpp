// Global grids of every layout users have, at the antimeridian (docs/terrain.md
// "Longitude wrap"): 256 columns once around the Earth with edges on the
// antimeridian (-180..180, 0..360) or half a pixel off it (ETOPO5's layout,
// west edge -180.0417: the column centred on +180 is absent, the first
// column supplies it), and 257 columns whose last repeats the first
// (grid-registered, -180..180 and 0..360). Each is tiled in both global
// schemes; every sample of the finest zoom (`extract`) is compared with a
// bilinear brute force written here that wraps longitudes, not with
// gdalwarp (which mis-samples the half-pixel layout's eastern hemisphere).
#include <gtest/gtest.h>

#include <gdal.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "raster_fixtures.hpp"
#include "test_support.hpp"

using namespace globe_test;

namespace {

constexpr int kColumns = 256;                  // distinct longitudes
constexpr double kStepDeg = 360.0 / kColumns;  // 1.40625 degrees
constexpr int kRows = 128;                     // pixel-is-area rows from 90 to -90
constexpr double kPi = 3.14159265358979323846;

// The surface at distinct longitude index i (mod 256) and row j: smooth
// relief plus a rough hash, so a wrong neighbour shows by hundreds of metres.
double surface(int64_t i, int j) {
  i = ((i % kColumns) + kColumns) % kColumns;
  const double lon = i * kStepDeg, lat = 90 - (j + 0.5) * 180.0 / kRows;
  uint32_t hsh = uint32_t(i) * 2654435761u ^ uint32_t(j) * 40503u;
  hsh ^= hsh >> 13;
  hsh *= 0x5bd1e995u;
  hsh ^= hsh >> 15;
  return 400 * std::sin(3 * lon * kPi / 180) * std::cos(lat * kPi / 180) + (hsh % 600) - 300.0;
}

struct Layout {
  const char* name;
  int columns;    // 256 (once around) or 257 (last column repeats the first)
  double west;    // west edge of the first pixel
  int64_t first;  // distinct longitude index of the first column
};

// The brute force: bilinear between the pixel centres around (lon, lat),
// longitudes wrapped (centre of distinct index i at first_lon + i * step).
double expected(const Layout& l, double lon, double lat) {
  const double first_lon = l.west + kStepDeg / 2;
  double u = (lon - first_lon) / kStepDeg;
  u -= std::floor(u / kColumns) * kColumns;  // 0 .. 256
  const double v = (90 - lat) / (180.0 / kRows) - 0.5;
  const int64_t i = int64_t(std::floor(u));
  const int j = int(std::floor(v));
  const double a = u - i, b = v - j;
  auto at = [&](int64_t x, int y) { return surface(l.first + x, y); };
  return (1 - b) * ((1 - a) * at(i, j) + a * at(i + 1, j)) +
         b * ((1 - a) * at(i, j + 1) + a * at(i + 1, j + 1));
}

// Tiles the layout's grid (with `options`) and compares every finest sample
// with the brute force: within half the height `step` plus 0.05 m.
void check_wrap(const Layout& layout, const std::string& tiling, const std::string& options,
                double step) {
  TempDir dir;
  const double gt[6] = {layout.west, kStepDeg, 0, 90, 0, -180.0 / kRows};
  const std::string dem = (dir / "g.tif").string();
  write_dem(dem, layout.columns, kRows, gt, "EPSG:4326", GDT_Float32,
            [&](int x, int y) { return surface(layout.first + x, y); });
  const std::string pkg = (dir / "g.mbtiles").string(), out = (dir / "z.tif").string();
  const RunResult built =
      run(tiler() + " terrain -q --tiling " + tiling + " " + options + " " + dem + " -o " + pkg,
          dir.path());
  ASSERT_EQ(built.exit_code, 0) << built.err;
  const RunResult info = run(tiler() + " info " + pkg, dir.path());
  const size_t at = info.out.find("  maxzoom ");
  ASSERT_NE(at, std::string::npos) << info.out;
  const int zoom = std::stoi(info.out.substr(at + 10));
  const RunResult ex = run(
      tiler() + " extract " + pkg + " --zoom " + std::to_string(zoom) + " -o " + out, dir.path());
  ASSERT_EQ(ex.exit_code, 0) << ex.err;

  gdal_setup();
  GDALDatasetH ds = GDALOpen(out.c_str(), GA_ReadOnly);
  ASSERT_NE(ds, nullptr);
  double g[6];
  GDALGetGeoTransform(ds, g);
  const int w = GDALGetRasterXSize(ds), h = GDALGetRasterYSize(ds);
  std::vector<float> z(size_t(w) * h);
  ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Read, 0, 0, w, h, z.data(), w, h, GDT_Float32,
                         0, 0),
            CE_None);
  GDALClose(ds);
  const bool mercator = tiling == "webmercator";
  const double lat_limit = 90 - 90.0 / kRows;  // the outermost rows' centres
  double worst = 0, worst_lon = 0, worst_lat = 0;
  size_t compared = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double lon = g[0] + (x + 0.5) * g[1], lat = g[3] + (y + 0.5) * g[5];
      if (mercator) {
        lon = lon / 6378137.0 * 180 / kPi;
        lat = std::atan(std::sinh(lat / 6378137.0)) * 180 / kPi;
      }
      if (std::fabs(lat) > lat_limit || std::fabs(lon) > 180 + 1e-9) continue;
      const double d = std::fabs(z[size_t(y) * w + x] - expected(layout, lon, lat));
      ++compared;
      if (d > worst) worst = d, worst_lon = lon, worst_lat = lat;
    }
  EXPECT_GT(compared, size_t(w) * h / 2);
  EXPECT_LE(worst, step / 2 + 0.05)
      << layout.name << " in " << tiling << ": worst at " << worst_lon << ", " << worst_lat;
  std::printf("%s, %s zoom %d: %zu samples, max error %.4f m\n", layout.name, tiling.c_str(), zoom,
              compared, worst);
}

class AntimeridianWrap : public ::testing::TestWithParam<std::tuple<Layout, std::string>> {};

TEST_P(AntimeridianWrap, EverySampleIsTheWrappedBilinear) {
  // The default step for float DEMs, 0.01 m: heights to 700 m keep the
  // warp in double precision.
  check_wrap(std::get<0>(GetParam()), std::get<1>(GetParam()), "", 0.01);
}

const Layout kLayouts[] = {
    {"edges_on_antimeridian_256", 256, -180.0, 0},                  // centres +-179.3
    {"etopo5_half_pixel_west_256", 256, -180.0 - kStepDeg / 2, 0},  // centres -180 .. 178.6
    {"zero_to_360_256", 256, 0.0, 0},
    {"zero_centred_0_to_360_256", 256, -kStepDeg / 2, 0},
    {"grid_registered_180_257", 257, -180.0 - kStepDeg / 2, 0},  // centres -180 .. 180
    {"grid_registered_360_257", 257, -kStepDeg / 2, 0},          // centres 0 .. 360
};

std::string name_of(const ::testing::TestParamInfo<std::tuple<Layout, std::string>>& p) {
  return std::string(std::get<0>(p.param).name) + "_" + std::get<1>(p.param);
}

INSTANTIATE_TEST_SUITE_P(Layouts, AntimeridianWrap,
                         ::testing::Combine(::testing::ValuesIn(kLayouts),
                                            ::testing::Values(std::string("geodetic"),
                                                              std::string("webmercator"))),
                         name_of);

}  // namespace

TEST(AntimeridianWrapSingle, EverySampleIsTheWrappedBilinearInSinglePrecision) {
  // At a 0.1 m step the warp works in single precision (docs/terrain.md
  // "Working precision"): the same layouts at the antimeridian, against the
  // same brute force.
  for (const Layout& layout : {kLayouts[1], kLayouts[4]})
    for (const std::string tiling : {"geodetic", "webmercator"}) {
      SCOPED_TRACE(std::string(layout.name) + " " + tiling);
      check_wrap(layout, tiling, "--precision 0.1", 0.1);
    }
}
