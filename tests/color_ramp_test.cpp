// The elevation ramp's transfer functions: gdaldem color-relief files read
// and tabulated as gdaldem itself colours the same values (the gdaldem
// program is the reference), the built-in hypsometric ramp's sea/land
// split, percentiles, and clear errors for bad colour files.
#include <gtest/gtest.h>

#include <fstream>

#include "app/color_relief_file.hpp"
#include "raster_fixtures.hpp"
#include "render/color_ramp.hpp"
#include "runtime/errors.hpp"
#include "test_support.hpp"

namespace {

using namespace globe_test;
using globe::viewer::builtin_ramp;
using globe::viewer::percentile_range;
using globe::viewer::read_color_relief_file;
using globe::viewer::Rgba;
using globe::viewer::tabulate;

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

// Colours `values` (one row) with the gdaldem program and returns RGBA per value.
std::vector<Rgba> gdaldem_colors(const std::vector<double>& values, const fs::path& colors,
                                 const fs::path& dir) {
  const std::string in = (dir / "values.tif").string(), out = (dir / "colors.tif").string();
  const double gt[6] = {0, 1, 0, 0, 0, -1};
  write_dem(in, static_cast<int>(values.size()), 1, gt, "EPSG:32632", GDT_Float64,
            [&](int x, int) { return values[x]; });
  const RunResult r =
      run("gdaldem color-relief -q -alpha " + in + " " + colors.string() + " " + out, dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  GDALDatasetH ds = GDALOpen(out.c_str(), GA_ReadOnly);
  std::vector<Rgba> c(values.size());
  if (!ds) return c;
  for (int b = 0; b < 4; ++b) {
    std::vector<uint8_t> row(values.size());
    EXPECT_EQ(GDALRasterIO(GDALGetRasterBand(ds, b + 1), GF_Read, 0, 0, int(values.size()), 1,
                           row.data(), int(values.size()), 1, GDT_Byte, 0, 0),
              CE_None);
    for (size_t i = 0; i < values.size(); ++i)
      c[i][b] = row[i];
  }
  GDALClose(ds);
  return c;
}

TEST(ColorRamp, ColourFileColoursValuesAsGdaldemDoes) {
  TempDir dir;
  const fs::path colors = dir / "ramp.txt";
  // Absolute and percentage stops, a named colour, separators gdaldem
  // accepts, a comment and a no-data line.
  write_text(colors,
             "# a test ramp\n"
             "-500 0 0 128\n"
             "0,0,128,255\n"
             "0.5 40 160 40\n"
             "25% 200 200 100 200\n"
             "1200:180:120:60\n"
             "100% white\n"
             "nv 0 0 0 0\n");
  const auto file = read_color_relief_file(colors.string());
  ASSERT_TRUE(file.nodata);
  EXPECT_EQ((*file.nodata)[3], 0);
  // gdaldem resolves percentages against the raster's min and max: the
  // values below span exactly -800..3000.
  std::vector<double> values;
  for (double v = -800; v <= 3000; v += 7.3)
    values.push_back(v);
  values.push_back(3000);
  const auto table = tabulate(file.ramp, -800, 3000);
  const auto want = gdaldem_colors(values, colors, dir.path());
  int worst = 0;
  for (size_t i = 0; i < values.size(); ++i) {
    const Rgba got = table.at(values[i]);
    for (int b = 0; b < 4; ++b) {
      const int d = std::abs(int(got[b]) - int(want[i][b]));
      worst = std::max(worst, d);
      // One table entry spans (3000 + 800) / 4095 m; the steepest blend here
      // changes 255 levels over 0.5 m (0 -> 0.5 m), so allow a step there.
      if (values[i] < -1 || values[i] > 2) {
        EXPECT_LE(d, 2) << "value " << values[i] << " band " << b;
      }
    }
  }
  std::printf("worst channel difference to gdaldem: %d\n", worst);
}

TEST(ColorRamp, HypsometricSplitsSeaAndLandAtZero) {
  const auto t = tabulate(builtin_ramp("hypsometric", -9000, 6000), -9000, 6000);
  const Rgba sea = t.at(-20), land = t.at(20), deep = t.at(-9000), peak = t.at(6000);
  EXPECT_GT(sea[2], sea[0] + 40) << "just below 0 m is blue";
  EXPECT_GT(land[1], land[2] + 30) << "just above 0 m is green";
  EXPECT_LT(deep[0] + deep[1] + deep[2], sea[0] + sea[1] + sea[2]) << "deeper is darker";
  EXPECT_GT(peak[0], 240) << "peaks are white";
  // Without sea the land ramp spans the data: its lowest point is green.
  const auto m = tabulate(builtin_ramp("hypsometric", 2000, 6800), 2000, 6800);
  EXPECT_GT(m.at(2000)[1], m.at(2000)[2] + 30);
  EXPECT_GT(m.at(6800)[0], 240);
}

TEST(ColorRamp, PercentilesClipTheRange) {
  std::vector<float> v;
  for (int i = 0; i <= 1000; ++i)
    v.push_back(static_cast<float>(i));
  v.push_back(1e6f);  // one outlier
  auto all = v;
  EXPECT_EQ(percentile_range(all, 0), (std::pair<double, double>{0, 1e6}));
  const auto [lo, hi] = percentile_range(v, 1);
  EXPECT_NEAR(lo, 10, 1);
  EXPECT_NEAR(hi, 991, 1);
}

TEST(ColorRamp, BadColourFilesNameFileAndLine) {
  TempDir dir;
  const auto message = [&](const std::string& text) -> std::string {
    write_text(dir / "c.txt", text);
    try {
      read_color_relief_file((dir / "c.txt").string());
    } catch (const globe::InputError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_NE(message("0 0 0 0\n100 0 300 0\n").find("c.txt:2: colour component '300'"),
            std::string::npos);
  EXPECT_NE(message("abc 1 2 3\n").find("c.txt:1: value 'abc' is not a number"), std::string::npos);
  EXPECT_NE(message("0 mauve\n").find("unknown colour name 'mauve'"), std::string::npos);
  EXPECT_NE(message("0 1 2\n").find("expected 2, 4 or 5 fields"), std::string::npos);
  EXPECT_NE(message("# nothing\nnv 0 0 0\n").find("no colour stops"), std::string::npos);
  EXPECT_NE(message("").find("no colour stops"), std::string::npos);
  try {
    read_color_relief_file((dir / "missing.txt").string());
    ADD_FAILURE() << "no error for a missing file";
  } catch (const globe::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.txt: cannot read"), std::string::npos);
  }
}

}  // namespace
