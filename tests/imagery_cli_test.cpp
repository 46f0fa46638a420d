// globe-tiler imagery on synthetic rasters: determinism, alignment with a
// terrain package, alpha from nodata / alpha band / mask, empty and
// identical tiles, tile size, the inspection commands, and bad input.
#include <gtest/gtest.h>

#include <set>

#include "image_fixtures.hpp"
#include "test_support.hpp"
#include "tileformat/package.hpp"

namespace globe_test {
namespace {

const double kUtmGt[6] = {500000, 10, 0, 5200000, 0, -10};  // UTM 32N, 10 m pixels
const char* kUtm = "EPSG:32632";

enum class Alpha { kNone, kBand, kMask };

// Writes a Byte GeoTIFF of `bands` bands; value(b, x, y) gives each pixel.
// kBand adds an alpha band (from alpha(x, y)); kMask an internal mask.
void write_image(const std::string& path, int w, int h, const double gt[6], int bands,
                 const std::function<int(int, int, int)>& value, Alpha alpha = Alpha::kNone,
                 const std::function<int(int, int)>& alpha_at = nullptr,
                 const std::string& srs = kUtm) {
  gdal_setup();
  const int total = bands + (alpha == Alpha::kBand ? 1 : 0);
  GDALDatasetH ds =
      GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), w, h, total, GDT_Byte, nullptr);
  GDALSetGeoTransform(ds, const_cast<double*>(gt));
  if (!srs.empty()) {
    OGRSpatialReferenceH s = OSRNewSpatialReference(nullptr);
    OSRSetFromUserInput(s, srs.c_str());
    GDALSetSpatialRef(ds, s);
    OSRRelease(s);
  }
  std::vector<uint8_t> row(w);
  auto fill = [&](GDALRasterBandH band, const std::function<int(int, int)>& f) {
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x)
        row[x] = static_cast<uint8_t>(f(x, y));
      ASSERT_EQ(GDALRasterIO(band, GF_Write, 0, y, w, 1, row.data(), w, 1, GDT_Byte, 0, 0),
                CE_None);
    }
  };
  for (int b = 0; b < bands; ++b)
    fill(GDALGetRasterBand(ds, b + 1), [&](int x, int y) { return value(b, x, y); });
  if (bands == 3)
    for (int b = 0; b < 3; ++b)
      GDALSetRasterColorInterpretation(GDALGetRasterBand(ds, b + 1),
                                       GDALColorInterp(GCI_RedBand + b));
  if (alpha == Alpha::kBand) {
    GDALSetRasterColorInterpretation(GDALGetRasterBand(ds, total), GCI_AlphaBand);
    fill(GDALGetRasterBand(ds, total), alpha_at);
  } else if (alpha == Alpha::kMask) {
    GDALCreateDatasetMaskBand(ds, GMF_PER_DATASET);
    fill(GDALGetMaskBand(GDALGetRasterBand(ds, 1)), alpha_at);
  }
  GDALClose(ds);
}

int pattern(int b, int x, int y) {
  return (x * 7 + y * 3 + b * 50) % 251;
}

// Tile ids of one zoom (or all).
std::set<std::string> tile_ids(const fs::path& pkg, std::optional<int> zoom = std::nullopt) {
  tileformat::PackageReader r(pkg.string());
  std::set<std::string> ids;
  r.for_each_tile([&](tileformat::TileId id, std::span<const uint8_t>) { ids.insert(id.str()); },
                  zoom);
  return ids;
}

class ImageryCli : public ::testing::Test {
 protected:
  RunResult imagery(const std::string& args) {
    return run(tiler() + " imagery " + args + " -q", tmp.path());
  }
  TempDir tmp;
};

TEST_F(ImageryCli, SameOutputForAnyThreadCount) {
  const fs::path img = tmp / "rgb.tif";
  write_image(img.string(), 700, 600, kUtmGt, 3, pattern);
  for (const char* fmt : {"png", "jpg"}) {
    // Same relative output name (the command line is in the metadata).
    for (const char* j : {"1", "2"}) {
      const fs::path dir = tmp / (std::string(fmt) + j);
      fs::create_directories(dir);
      const RunResult r = run("cd " + dir.string() + " && " + tiler() + " imagery ../rgb.tif -q" +
                                  " -o out.mbtiles --format " + fmt + " -j " + j,
                              tmp.path());
      ASSERT_EQ(r.exit_code, 0) << r.err;
    }
    const bool same = read_file(tmp / (std::string(fmt) + "1") / "out.mbtiles") ==
                      read_file(tmp / (std::string(fmt) + "2") / "out.mbtiles");
    EXPECT_TRUE(same) << fmt << ": -j1 and -j2 packages differ";
  }
}

// A terrain package and an image package of the same field, the image built
// --like the (local) terrain: same tiling, same tile ids at every zoom, and
// the image's gray value at each terrain sample's position equals the height
// there (both are the field).
TEST_F(ImageryCli, AlignsWithATerrainPackageOfTheSameArea) {
  auto field = [](double x, double y) {
    return 120 + 60 * std::sin(x / 37.0) * std::cos(y / 23.0);
  };
  const fs::path dem = tmp / "dem.tif", img = tmp / "img.tif";
  write_dem(dem.string(), 300, 260, kUtmGt, kUtm, GDT_Float32,
            [&](int x, int y) { return field(x + 0.5, y + 0.5); });
  write_image(img.string(), 300, 260, kUtmGt, 1,
              [&](int, int x, int y) { return int(std::lround(field(x + 0.5, y + 0.5))); });
  const fs::path terrain = tmp / "terrain.mbtiles", image = tmp / "image.mbtiles";
  ASSERT_EQ(run(tiler() + " terrain " + dem.string() + " --tiling local --block-size 65 -q -o " +
                    terrain.string(),
                tmp.path())
                .exit_code,
            0);
  const RunResult r =
      imagery(img.string() + " --like " + terrain.string() + " --max-zoom 2 --tile-size 256 -o " +
              image.string() + " --resampling bilinear");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  tileformat::PackageReader tr(terrain.string()), ir(image.string());
  for (const char* key : {"globe:scheme", "globe:crs", "globe:origin", "globe:root_size"})
    EXPECT_EQ(tr.meta(key), ir.meta(key)) << key;
  for (int z = 0; z <= 2; ++z)
    EXPECT_EQ(tile_ids(terrain, z), tile_ids(image, z)) << "zoom " << z;

  // Heights and gray values at the same ground positions (zoom 2).
  ASSERT_EQ(
      run(tiler() + " extract " + terrain.string() + " --zoom 2 -o " + (tmp / "t.tif").string(),
          tmp.path())
          .exit_code,
      0);
  ASSERT_EQ(run(tiler() + " extract " + image.string() + " --zoom 2 -o " + (tmp / "i.tif").string(),
                tmp.path())
                .exit_code,
            0);
  const Raster heights = read_raster((tmp / "t.tif").string());
  const Image gray = read_image((tmp / "i.tif").string());
  size_t compared = 0;
  double worst = 0;
  for (int y = 0; y < heights.height; y += 3)
    for (int x = 0; x < heights.width; x += 3) {
      const double h = heights.at(x, y);
      if (std::isnan(h)) continue;
      const double mx = heights.gt[0] + (x + 0.5) * heights.gt[1],
                   my = heights.gt[3] + (y + 0.5) * heights.gt[5];
      const int ix = int(std::floor((mx - gray.gt[0]) / gray.gt[1])),
                iy = int(std::floor((my - gray.gt[3]) / gray.gt[5]));
      if (ix < 0 || iy < 0 || ix >= gray.width || iy >= gray.height) continue;
      if (gray.at(1, ix, iy) != 255) continue;
      ++compared;
      worst = std::max(worst, std::abs(h - gray.at(0, ix, iy)));
    }
  EXPECT_GT(compared, 1000u);
  // Nearest pixel vs sample within a pixel: the field changes < 3 per pixel.
  EXPECT_LT(worst, 4.0) << "image and terrain disagree on where the data lies";
}

TEST_F(ImageryCli, AlphaFromNodataAlphaBandAndMask) {
  // Left half valid, right half "no data" in three ways.
  auto left = [](int x, int) { return x < 350 ? 255 : 0; };
  const fs::path nodata = tmp / "nodata.tif", band = tmp / "band.tif", mask = tmp / "mask.tif";
  write_image(nodata.string(), 700, 600, kUtmGt, 3,
              [&](int b, int x, int y) { return x < 350 ? 1 + pattern(b, x, y) % 200 : 0; });
  write_image(band.string(), 700, 600, kUtmGt, 3, pattern, Alpha::kBand, left);
  write_image(mask.string(), 700, 600, kUtmGt, 3, pattern, Alpha::kMask, left);
  for (const auto& [src, extra] :
       {std::pair{nodata, std::string(" --nodata 0")}, std::pair{band, std::string()},
        std::pair{mask, std::string()}}) {
    const fs::path pkg = tmp / (src.stem().string() + ".mbtiles");
    const RunResult r = imagery(src.string() + extra + " --resampling near -o " + pkg.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    tileformat::PackageReader reader(pkg.string());
    const int z = std::stoi(*reader.meta("maxzoom"));
    const fs::path out = tmp / (src.stem().string() + "_extract.tif");
    ASSERT_EQ(run(tiler() + " extract " + pkg.string() + " --zoom " + std::to_string(z) + " -o " +
                      out.string(),
                  tmp.path())
                  .exit_code,
              0);
    const Image im = read_image(out.string());
    // Where the valid half lands: gdalwarp of the alpha-band source (all
    // three sources mark the same half valid). Without the nodata / alpha /
    // mask, twice as many pixels would be opaque.
    const Image ref = warp_image_like(band.string(), im, "near", (tmp / "ref.tif").string(), {},
                                      0.125, "EPSG:3857");
    size_t opaque = 0, ref_opaque = 0, wrong = 0;
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x) {
        const uint8_t a = im.at(3, x, y);
        opaque += a == 255;
        ref_opaque += ref.at(3, x, y) == 255;
        if (ref.at(3, x, y) == 0 && a == 255) ++wrong;
      }
    EXPECT_GT(opaque, 1000u) << src;
    EXPECT_NEAR(double(opaque), double(ref_opaque), 0.02 * ref_opaque) << src;
    EXPECT_LT(wrong, opaque / 100) << src << ": masked pixels came out opaque";
  }
}

TEST_F(ImageryCli, SkipsEmptyTilesAndStoresIdenticalTilesOnce) {
  // A uniform image: all finest tiles inside it are identical.
  const fs::path img = tmp / "flat.tif";
  const double gt[6] = {-2000000, 50, 0, 2000000, 0, -50};
  write_image(
      img.string(), 2048, 2048, gt, 3, [](int b, int, int) { return 40 + b; }, Alpha::kNone,
      nullptr, "EPSG:3857");
  const fs::path pkg = tmp / "flat.mbtiles";
  ASSERT_EQ(imagery(img.string() + " --max-zoom 12 -o " + pkg.string()).exit_code, 0);
  tileformat::PackageReader r(pkg.string());
  EXPECT_LT(r.unique_blobs(), tile_ids(pkg).size() / 4);

  // Data only in the north-west corner of a wide area: tiles elsewhere are empty.
  const fs::path corner = tmp / "corner.tif";
  write_image(
      corner.string(), 2048, 2048, gt, 3,
      [](int b, int x, int y) { return x < 300 && y < 300 ? 100 + b : 0; }, Alpha::kNone, nullptr,
      "EPSG:3857");
  const fs::path cpkg = tmp / "corner.mbtiles";
  ASSERT_EQ(imagery(corner.string() + " --nodata 0 --max-zoom 12 -o " + cpkg.string()).exit_code,
            0);
  EXPECT_LT(tile_ids(cpkg, 12).size(), tile_ids(pkg, 12).size() / 10);
}

TEST_F(ImageryCli, TileSize512IsReadByGdal) {
  const fs::path img = tmp / "rgb.tif";
  write_image(img.string(), 700, 600, kUtmGt, 3, pattern);
  const fs::path pkg = tmp / "t512.mbtiles";
  // (GDAL 3.6 detects 512 px tiles in PNG and JPEG packages, not in WebP.)
  const RunResult r = imagery(img.string() + " --tile-size 512 --format jpg -o " + pkg.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  gdal_setup();
  GDALDatasetH ds = GDALOpen(pkg.string().c_str(), GA_ReadOnly);
  ASSERT_NE(ds, nullptr) << "GDAL's MBTiles driver cannot open " << pkg;
  int bx = 0, by = 0;
  GDALGetBlockSize(GDALGetRasterBand(ds, 1), &bx, &by);
  EXPECT_EQ(bx, 512);
  GDALClose(ds);
  tileformat::PackageReader reader(pkg.string());
  for (const char* key : {"name", "format", "bounds", "center", "minzoom", "maxzoom", "type",
                          "version", "description"})
    EXPECT_TRUE(reader.meta(key)) << "MBTiles 1.3 key " << key;
  EXPECT_EQ(*reader.meta("format"), "jpg");
  EXPECT_EQ(run(tiler() + " validate " + pkg.string(), tmp.path()).exit_code, 0);
}

TEST_F(ImageryCli, CrossesTheAntimeridian) {
  const double gt[6] = {170, 0.05, 0, 10, 0, -0.05};  // 170E .. 190E
  const fs::path img = tmp / "am.tif";
  write_image(img.string(), 400, 200, gt, 3, pattern, Alpha::kNone, nullptr, "EPSG:4326");
  const fs::path pkg = tmp / "am.mbtiles";
  const RunResult r = imagery(img.string() + " --max-zoom 5 -o " + pkg.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto ids = tile_ids(pkg, 5);
  EXPECT_TRUE(ids.count("5/0/15") || ids.count("5/0/16")) << "no tile east of the antimeridian";
  EXPECT_TRUE(ids.count("5/31/15") || ids.count("5/31/16")) << "no tile west of it";
  EXPECT_EQ(run(tiler() + " validate " + pkg.string(), tmp.path()).exit_code, 0);
}

TEST_F(ImageryCli, InfoValidateAndExtractKnowImagePackages) {
  const fs::path img = tmp / "rgb.tif";
  write_image(img.string(), 700, 600, kUtmGt, 3, pattern);
  const fs::path pkg = tmp / "p.mbtiles";
  ASSERT_EQ(imagery(img.string() + " --format jpg -o " + pkg.string()).exit_code, 0);
  const RunResult info = run(tiler() + " info " + pkg.string(), tmp.path());
  EXPECT_EQ(info.exit_code, 0);
  EXPECT_NE(info.out.find("image: 256 x 256 px tiles, RGB + alpha"), std::string::npos) << info.out;
  // A damaged tile: validate names it and fails; extract refuses it.
  {
    tileformat::SqliteDb db(pkg.string(), tileformat::SqliteDb::Mode::kReadWriteCreate);
    db.exec(
        "UPDATE blobs SET tile_data = X'FFD8FF00112233' WHERE blob_id = "
        "(SELECT MAX(blob_id) FROM blobs)");
  }
  const RunResult v = run(tiler() + " validate " + pkg.string(), tmp.path());
  EXPECT_EQ(v.exit_code, 1) << v.out;
  EXPECT_NE(v.out.find("tileformat §8"), std::string::npos) << v.out;
}

TEST_F(ImageryCli, BadInputGetsAClearErrorAndNoOutput) {
  const fs::path good = tmp / "good.tif";
  write_image(good.string(), 300, 200, kUtmGt, 3, pattern);
  const fs::path nocrs = tmp / "nocrs.tif";
  write_image(nocrs.string(), 300, 200, kUtmGt, 3, pattern, Alpha::kNone, nullptr, "");
  const fs::path blank = tmp / "blank.tif";
  write_image(blank.string(), 300, 200, kUtmGt, 3, [](int, int, int) { return 0; });
  const fs::path text = tmp / "text.tif";
  std::ofstream(text) << "not a raster\n";
  const fs::path truncated = tmp / "truncated.tif";
  {
    const std::string bytes = read_file(good);
    std::ofstream(truncated, std::ios::binary) << bytes.substr(0, bytes.size() / 3);
  }
  const fs::path out = tmp / "out.mbtiles";
  struct Case {
    std::string args;
    int code;
    std::string says;
  };
  const std::vector<Case> cases = {
      {(tmp / "missing.tif").string(), 1, "missing.tif"},
      {text.string(), 1, "text.tif"},
      {truncated.string(), 1, "truncated.tif"},
      {nocrs.string(), 1, "--s_srs"},
      {blank.string() + " --nodata 0", 1, "transparent"},
      {good.string() + " --bands 3,2", 2, "--bands"},  // 2 = gray + alpha is fine: see below
      {good.string() + " --bands 4,2,1", 2, "has 3 bands"},
      {good.string() + " --bands 1,2,3,4,5", 2, "--bands"},
      {good.string() + " --bands x", 2, "--bands"},
      {good.string() + " --format gif", 2, "--format"},
      {good.string() + " --tile-size 300", 2, "--tile-size"},
      {good.string() + " --resampling best", 2, "--resampling"},
  };
  for (const Case& c : cases) {
    const RunResult r = imagery(c.args + " -o " + out.string());
    if (c.args.find("--bands 3,2") != std::string::npos) {
      EXPECT_EQ(r.exit_code, 0) << c.args << ": gray + alpha bands should work\n" << r.err;
      fs::remove(out);
      continue;
    }
    EXPECT_EQ(r.exit_code, c.code) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_FALSE(fs::exists(out)) << c.args;
    EXPECT_FALSE(fs::exists(out.string() + ".tmp")) << c.args;
    EXPECT_FALSE(fs::exists(out.string() + ".staging")) << c.args;
  }
  // An existing output is kept without --force.
  std::ofstream(out) << "keep me";
  EXPECT_EQ(imagery(good.string() + " -o " + out.string()).exit_code, 3);
  EXPECT_EQ(read_file(out), "keep me");
}

}  // namespace
}  // namespace globe_test
