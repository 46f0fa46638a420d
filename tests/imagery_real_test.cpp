// Imagery on real samples: tile, read back through GDAL's MBTiles driver, and
// compare with gdalwarp of the source onto the same grid, with exact
// reprojection on both sides (--transform-error 0, gdalwarp -et 0).
//   - PNG: every opaque pixel equals gdalwarp's. When downsampling (bluemarble
//     at z3), only with nearest neighbour: GDAL widens interpolation kernels
//     by the scale it measures per warped chunk, and our chunks are 4 x 4
//     tile windows, gdalwarp's the whole output.
//   - JPEG / WebP at quality 90: PSNR >= 35 dB.
#include <gtest/gtest.h>

#include <ostream>

#include "image_fixtures.hpp"
#include "test_support.hpp"

namespace globe_test {
namespace {

struct ImageCase {
  const char* name;
  const char* file;
  const char* options;  // extra globe-tiler imagery options
  std::vector<int> bands;
  int colour;
  const char* resampling;
  bool exact;       // equal pixels
  double min_psnr;  // else
};

class RealImagery : public ::testing::TestWithParam<ImageCase> {};

// ctest lists parameterised tests with their value: the case's name.
[[maybe_unused]] void PrintTo(const ImageCase& c, std::ostream* os) {
  *os << c.name;
}

TEST_P(RealImagery, ReadsBackThroughGdalLikeGdalwarp) {
  const ImageCase& c = GetParam();
  TempDir tmp;
  const fs::path src = sample(c.file);
  const fs::path pkg = tmp / "out.mbtiles";
  const RunResult r =
      run(tiler() + " imagery " + src.string() + " -o " + pkg.string() +
              " -q --transform-error 0 --resampling " + c.resampling + " " + c.options,
          tmp.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const RunResult v = run(tiler() + " validate " + pkg.string(), tmp.path());
  EXPECT_EQ(v.exit_code, 0) << v.out;

  // GDAL's MBTiles driver opens the package at its finest zoom.
  const Image ours = read_image(pkg.string());
  ASSERT_EQ(ours.bands, 4) << "GDAL could not read " << pkg;  // gray is read as RGBA
  ASSERT_GT(ours.width, 100);
  // In EPSG:3857 itself: the WKT1 GDAL reports for MBTiles carries
  // +nadgrids=@null, which would drop the source's datum shift.
  const Image ref = warp_image_like(src.string(), ours, c.resampling, (tmp / "ref.tif").string(),
                                    c.bands, 0.0, "EPSG:3857");
  ASSERT_EQ(ref.width, ours.width);
  const ImageDiff d = compare_images(ours, ref, c.colour);
  const size_t pixels = size_t(ours.width) * ours.height;
  EXPECT_GT(d.compared, pixels / 4) << "too few pixels covered by both";
  EXPECT_LT(d.coverage_differs, pixels / 200) << "coverage differs from gdalwarp's";
  if (c.exact)
    EXPECT_EQ(d.max_diff, 0) << "PSNR " << d.psnr << " dB";
  else
    EXPECT_GE(d.psnr, c.min_psnr) << "max difference " << d.max_diff;
  std::printf("%s: %zu pixels compared, PSNR %.1f dB, max diff %d, coverage differs %zu\n", c.name,
              d.compared, d.psnr, d.max_diff, d.coverage_differs);
}

INSTANTIATE_TEST_SUITE_P(
    Samples, RealImagery,
    ::testing::Values(
        ImageCase{"cbers20_png_near", "cbers20.tif", "", {}, 3, "near", true, 0},
        ImageCase{"cbers20_png_bilinear", "cbers20.tif", "", {}, 3, "bilinear", true, 0},
        ImageCase{"cbers20_jpg90",
                  "cbers20.tif",
                  "--format jpg --quality 90",
                  {},
                  3,
                  "bilinear",
                  false,
                  35},
        ImageCase{"landsat_321_jpg90",
                  "landsat.tif",
                  "--bands 3,2,1 --format jpg --quality 90",
                  {3, 2, 1},
                  3,
                  "bilinear",
                  false,
                  35},
        ImageCase{"landsat_4_gray_png", "landsat.tif", "--bands 4", {4}, 1, "near", true, 0},
        ImageCase{"bluemarble_png", "bluemarble.tif", "--max-zoom 3", {}, 3, "near", true, 0},
        ImageCase{"bluemarble_webp90",
                  "bluemarble.tif",
                  "--max-zoom 3 --format webp --quality 90",
                  {},
                  3,
                  "near",
                  false,
                  35}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace globe_test
