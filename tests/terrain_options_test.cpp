// globe-tiler terrain options on small generated DEMs: each test checks what
// the option promises, through info/extract/validate.
#include <gtest/gtest.h>

#include <cmath>

#include "raster_fixtures.hpp"
#include "test_support.hpp"
#include "tileformat/package.hpp"

using namespace globe_test;

namespace {

// A smooth 0.001-degree DEM near Zurich, 200 x 160 pixels, metres with decimals.
const double kGt[6] = {8.50, 0.001, 0, 47.40, 0, -0.001};
double height_at(int x, int y) {
  return 400.0 + 30.0 * std::sin(x * 0.05) + 0.7 * y + 0.25;
}

std::string make_dem(const TempDir& dir, const std::string& name = "dem.tif") {
  const auto path = (dir / name).string();
  write_dem(path, 200, 160, kGt, "EPSG:4326", GDT_Float32,
            [](int x, int y) { return height_at(x, y); });
  return path;
}

std::map<std::string, std::string> metadata(const std::string& pkg) {
  tileformat::PackageReader r(pkg);
  return r.metadata();
}

std::vector<tileformat::ZoomSummary> zooms(const std::string& pkg) {
  tileformat::PackageReader r(pkg);
  return r.zoom_summaries();
}

Raster extract(const TempDir& dir, const std::string& pkg, int zoom, const std::string& name) {
  const auto out = (dir / name).string();
  auto r =
      run(tiler() + " extract --force " + pkg + " --zoom " + std::to_string(zoom) + " -o " + out,
          dir.path());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return read_raster(out);
}

void build(const TempDir& dir, const std::string& args) {
  auto r = run(tiler() + " terrain -q " + args, dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
}

}  // namespace

TEST(TerrainOptions, SeveralInputsFormOneMosaic) {
  // The DEM split into west and east halves (different files) must give the
  // same package content as the whole DEM (nearest resampling: bilinear
  // cannot reach across files at the seam, in gdalwarp either).
  TempDir dir;
  const auto whole = make_dem(dir);
  const double west_gt[6] = {8.50, 0.001, 0, 47.40, 0, -0.001},
               east_gt[6] = {8.60, 0.001, 0, 47.40, 0, -0.001};
  write_dem((dir / "west.tif").string(), 100, 160, west_gt, "EPSG:4326", GDT_Float32,
            [](int x, int y) { return height_at(x, y); });
  write_dem((dir / "east.tif").string(), 100, 160, east_gt, "EPSG:4326", GDT_Float32,
            [](int x, int y) { return height_at(x + 100, y); });
  build(dir, "--resampling near " + whole + " -o " + (dir / "whole.mbtiles").string());
  build(dir, "--resampling near " + (dir / "west.tif").string() + " " +
                 (dir / "east.tif").string() + " -o " + (dir / "mosaic.mbtiles").string());
  const int z = std::stoi(metadata((dir / "whole.mbtiles").string()).at("maxzoom"));
  const Raster a = extract(dir, (dir / "whole.mbtiles").string(), z, "a.tif");
  const Raster b = extract(dir, (dir / "mosaic.mbtiles").string(), z, "b.tif");
  ASSERT_EQ(a.data.size(), b.data.size());
  EXPECT_EQ(a.valid_count(), b.valid_count());
  for (size_t i = 0; i < a.data.size(); ++i) {
    if (!std::isnan(a.data[i])) {
      ASSERT_EQ(a.data[i], b.data[i]) << "sample " << i;
    }
  }
}

TEST(TerrainOptions, MinzoomMetadataIsTheCoarsestZoomWritten) {
  // A DEM smaller than one sample spacing of zoom 0 has no valid sample there:
  // empty tiles are not written, and minzoom says so.
  TempDir dir;
  const auto dem = make_dem(dir);
  const auto pkg = (dir / "p.mbtiles").string();
  build(dir, dem + " -o " + pkg);
  ASSERT_GT(zooms(pkg).front().zoom, 0) << "the fixture should be too small for zoom 0";
  EXPECT_EQ(std::to_string(zooms(pkg).front().zoom), metadata(pkg).at("minzoom"));
}

TEST(TerrainOptions, BboxLimitsTheTiles) {
  TempDir dir;
  const auto dem = make_dem(dir);
  build(dir, dem + " -o " + (dir / "all.mbtiles").string());
  build(dir, dem + " --bbox 8.50,47.30,8.53,47.33 -o " + (dir / "part.mbtiles").string());
  const auto all = zooms((dir / "all.mbtiles").string()),
             part = zooms((dir / "part.mbtiles").string());
  ASSERT_EQ(all.back().zoom, part.back().zoom);
  EXPECT_LT(part.back().tiles, all.back().tiles);
  const auto b = metadata((dir / "part.mbtiles").string()).at("bounds");
  EXPECT_EQ(b.substr(0, b.find(',')), "8.5");
}

TEST(TerrainOptions, BlockSizePrecisionAndZoomRange) {
  TempDir dir;
  const auto dem = make_dem(dir);
  const auto pkg = (dir / "p.mbtiles").string();
  build(dir, dem + " --block-size 65 --precision 0.5 --min-zoom 8 -o " + pkg);
  const auto meta = metadata(pkg);
  EXPECT_EQ(meta.at("globe:block_size"), "65");
  EXPECT_EQ(meta.at("globe:height_step"), "0.5");
  EXPECT_EQ(meta.at("minzoom"), "8");
  EXPECT_EQ(zooms(pkg).front().zoom, 8);
  EXPECT_EQ(run(tiler() + " validate " + pkg, dir.path()).exit_code, 0);
  // Every height is a multiple of the step.
  const Raster r = extract(dir, pkg, std::stoi(meta.at("maxzoom")), "z.tif");
  for (double v : r.data) {
    if (!std::isnan(v)) {
      ASSERT_DOUBLE_EQ(v * 2, std::round(v * 2));
    }
  }
}

TEST(TerrainOptions, NodataOverrideMakesHoles) {
  // Heights of exactly 500 (a band of pixels) become holes with --nodata 500.
  TempDir dir;
  const auto path = (dir / "band.tif").string();
  write_dem(path, 200, 160, kGt, "EPSG:4326", GDT_Int16,
            [](int x, int y) { return (x >= 90 && x < 110) ? 500 : 100 + y; });
  build(dir, "--resampling near " + path + " -o " + (dir / "a.mbtiles").string());
  build(dir, "--resampling near --nodata 500 " + path + " -o " + (dir / "b.mbtiles").string());
  const int z = std::stoi(metadata((dir / "a.mbtiles").string()).at("maxzoom"));
  const Raster a = extract(dir, (dir / "a.mbtiles").string(), z, "a.tif");
  const Raster b = extract(dir, (dir / "b.mbtiles").string(), z, "b.tif");
  size_t holes = 0;
  for (size_t i = 0; i < a.data.size(); ++i) {
    if (std::isnan(a.data[i])) continue;
    if (a.data[i] == 500) {
      EXPECT_TRUE(std::isnan(b.data[i]));
      ++holes;
    } else {
      EXPECT_EQ(a.data[i], b.data[i]);
    }
  }
  EXPECT_GT(holes, 1000u);
}

TEST(TerrainOptions, LocalTilingInAnotherCrs) {
  // --t_srs picks the local tiling's CRS (here UTM 32N for a lon/lat DEM).
  TempDir dir;
  const auto dem = make_dem(dir);
  const auto pkg = (dir / "utm.mbtiles").string();
  build(dir, "--tiling local --t_srs EPSG:32632 " + dem + " -o " + pkg);
  const auto meta = metadata(pkg);
  EXPECT_EQ(meta.at("globe:scheme"), "local");
  EXPECT_NE(meta.at("globe:crs").find("UTM zone 32N"), std::string::npos);
  EXPECT_EQ(run(tiler() + " validate " + pkg, dir.path()).exit_code, 0);
  auto r =
      run(tiler() + " terrain -q --t_srs EPSG:32632 " + dem + " -o " + (dir / "x.mbtiles").string(),
          dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--t_srs applies to --tiling local only"), std::string::npos);
}

TEST(TerrainOptions, FineStepOnHighGroundKeepsDoublePrecision) {
  // Heights near 5000 m at --precision 0.0001: single precision would round
  // them by up to 3 steps (5000 * 2^-24 m), so the warp must stay in double
  // and every sample be gdalwarp's (-ot Float64) within half a step.
  TempDir dir;
  const auto path = (dir / "high.tif").string();
  write_dem(path, 200, 160, kGt, "EPSG:4326", GDT_Float64, [](int x, int y) {
    return 5000.0 + 30.0 * std::sin(x * 0.05) + 0.7 * y + 0.0001234 * x * y;
  });
  const auto pkg = (dir / "p.mbtiles").string();
  build(dir, "--precision 0.0001 " + path + " -o " + pkg);
  const Raster ours = extract(dir, pkg, std::stoi(metadata(pkg).at("maxzoom")), "z.tif");
  const Raster ref = gdalwarp_reference({path}, ours, "bilinear", dir.path());
  const HeightComparison c = compare_heights(ours, ref);
  EXPECT_GT(c.compared, 10000u);
  EXPECT_LE(c.max_diff, 0.0001 / 2 + 1e-7) << "p99.9 " << c.p999;
}
