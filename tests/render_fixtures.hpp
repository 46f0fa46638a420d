// Helpers of the viewer tests: running globe-view, reading PNG snapshots,
// comparing them with expected images (tolerance; the diff image is kept on
// failure).
#pragma once

#include <gdal.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "raster_fixtures.hpp"
#include "test_paths.hpp"
#include "test_support.hpp"

namespace globe_test {

inline std::string viewer() {
  return globe_test::paths::view();
}

// The viewer's sky (its clear colour) in an RGB snapshot pixel.
inline bool is_sky(const uint8_t* p) {
  return std::abs(int(p[0]) - 158) < 4 && std::abs(int(p[1]) - 184) < 4 &&
         std::abs(int(p[2]) - 209) < 4;
}

// Fractions of the terrain pixels (not sky) of an RGB snapshot that `pick`
// accepts; `terrain` counts them.
struct Census {
  size_t terrain = 0;
  template <class Pick>
  double fraction(const std::vector<uint8_t>& rgb, Pick pick) {
    size_t n = 0;
    terrain = 0;
    for (size_t i = 0; i + 2 < rgb.size(); i += 3) {
      if (is_sky(&rgb[i])) continue;
      ++terrain;
      if (pick(&rgb[i])) ++n;
    }
    return terrain ? double(n) / terrain : 0;
  }
};

inline std::vector<uint8_t> read_rgb(const std::string& path, int& w, int& h) {
  gdal_setup();
  GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
  if (!ds) return {};
  w = GDALGetRasterXSize(ds), h = GDALGetRasterYSize(ds);
  std::vector<uint8_t> rgb(size_t(w) * h * 3);
  for (int b = 0; b < 3; ++b)
    EXPECT_EQ(GDALRasterIO(GDALGetRasterBand(ds, b + 1), GF_Read, 0, 0, w, h, rgb.data() + b, w, h,
                           GDT_Byte, 3, w * 3),
              CE_None);
  GDALClose(ds);
  return rgb;
}

// The pixels of a snapshot that `pick` (an RGB pointer) accepts, row-major.
template <class Pick>
std::vector<bool> pixels_where(const std::string& png, int& w, int& h, Pick pick) {
  const std::vector<uint8_t> rgb = read_rgb(png, w, h);
  std::vector<bool> marked(size_t(w) * h);
  for (size_t i = 0; i < marked.size(); ++i)
    marked[i] = pick(&rgb[3 * i]);
  return marked;
}

// Pixels that are mostly red (lines drawn in #ff0000).
inline std::vector<bool> red_pixels(const std::string& png, int& w, int& h) {
  return pixels_where(png, w, h, [](const uint8_t* p) { return int(p[0]) - int(p[1]) > 60; });
}

// The share of a's marked pixels with one of b's within 1.5 px (a 3 x 3
// neighbourhood); `count`: a's marked pixels.
inline double near_share(const std::vector<bool>& a, const std::vector<bool>& b, int w, int h,
                         size_t& count) {
  size_t near = 0;
  count = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!a[size_t(y) * w + x]) continue;
      ++count;
      bool found = false;
      for (int dy = -1; dy <= 1 && !found; ++dy)
        for (int dx = -1; dx <= 1 && !found; ++dx) {
          const int xx = x + dx, yy = y + dy;
          found = xx >= 0 && yy >= 0 && xx < w && yy < h && b[size_t(yy) * w + xx];
        }
      near += found;
    }
  return count ? double(near) / count : 0;
}

// PSNR of two RGB snapshots of the same size (99 when equal).
inline double psnr(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  double se = 0;
  for (size_t i = 0; i < a.size(); ++i)
    se += (double(a[i]) - b[i]) * (double(a[i]) - b[i]);
  return se == 0 ? 99.0 : 10 * std::log10(255.0 * 255.0 / (se / double(a.size())));
}

// A magic lens's frame (--lens CX,CY,R): outside the circle byte for byte
// the frame without the lens, inside the frame with the lens's content
// everywhere (a pixel's width around the rim left out: the circle cuts those
// pixels). Returns the pixels compared inside.
inline size_t expect_lens_frame(const std::vector<uint8_t>& plain,
                                const std::vector<uint8_t>& everywhere,
                                const std::vector<uint8_t>& lens, int w, int h, double cx,
                                double cy, double r) {
  EXPECT_EQ(plain.size(), size_t(w) * h * 3);
  EXPECT_EQ(everywhere.size(), plain.size());
  EXPECT_EQ(lens.size(), plain.size());
  if (plain.size() != size_t(w) * h * 3 || everywhere.size() != plain.size() ||
      lens.size() != plain.size())
    return 0;
  size_t inside = 0, outside = 0, inside_equal = 0, outside_equal = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double d = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
      if (std::abs(d - r) <= 1) continue;
      const size_t i = (size_t(y) * w + x) * 3;
      const bool same = std::equal(&lens[i], &lens[i] + 3, d < r ? &everywhere[i] : &plain[i]);
      (d < r ? inside : outside)++;
      (d < r ? inside_equal : outside_equal) += same;
    }
  EXPECT_EQ(outside_equal, outside) << "pixels outside the lens changed";
  EXPECT_EQ(inside_equal, inside)
      << "pixels inside the lens differ from the frame with it everywhere";
  EXPECT_NE(plain, everywhere) << "the lens's content changes nothing here";
  return inside;
}

// Compares with the expected image; on failure writes <name>.actual.png and
// <name>.diff.png (|difference| x 8) under the build's render-diffs folder.
inline void expect_image(const std::string& actual, const std::string& name) {
  const std::string expected = globe_test::paths::test_data_dir() + "/render/" + name + ".png";
  int w = 0, h = 0, ew = 0, eh = 0;
  const auto a = read_rgb(actual, w, h);
  const auto e = read_rgb(expected, ew, eh);
  ASSERT_FALSE(e.empty()) << expected << " missing: run tests/data/render/make_expected.sh";
  ASSERT_EQ(w, ew);
  ASSERT_EQ(h, eh);
  size_t bad = 0;
  double sum = 0;
  std::vector<uint8_t> diff(a.size());
  for (size_t i = 0; i < a.size(); ++i) {
    const int d = std::abs(int(a[i]) - int(e[i]));
    sum += d;
    if (d > 24) ++bad;
    diff[i] = static_cast<uint8_t>(std::min(255, d * 8));
  }
  const double mean = sum / a.size();
  const bool ok = mean <= 1.5 && bad <= a.size() / 200;
  EXPECT_TRUE(ok) << name << ": mean |diff| " << mean << ", " << bad
                  << " channel values off by > 24";
  if (!ok) {
    const fs::path out = fs::path(globe_test::paths::render_diff_dir());
    fs::create_directories(out);
    fs::copy_file(actual, out / (name + ".actual.png"), fs::copy_options::overwrite_existing);
    GDALDatasetH mem = GDALCreate(GDALGetDriverByName("MEM"), "", w, h, 3, GDT_Byte, nullptr);
    for (int b = 0; b < 3; ++b)
      EXPECT_EQ(GDALRasterIO(GDALGetRasterBand(mem, b + 1), GF_Write, 0, 0, w, h, diff.data() + b,
                             w, h, GDT_Byte, 3, w * 3),
                CE_None);
    GDALClose(GDALCreateCopy(GDALGetDriverByName("PNG"), (out / (name + ".diff.png")).c_str(), mem,
                             FALSE, nullptr, nullptr, nullptr));
    GDALClose(mem);
    ADD_FAILURE() << "images kept in " << out;
  }
}

}  // namespace globe_test
