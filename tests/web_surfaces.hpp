// Analytic surfaces the web export tests build packages from: known heights
// everywhere, so references need no decoder of the project's.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

#include <gdal.h>

#include "raster_fixtures.hpp"
#include "test_support.hpp"

namespace globe_test {

inline constexpr double kPi = 3.14159265358979323846;

// Analytic surfaces: base + amp sin(kx (lon - west)) cos(ky (lat - south))
// over a lon/lat box, written at `source` degrees (pixels as areas).
struct Surface {
  double west, east, south, north, source, base, amp, kx, ky;  // k: radians per degree
  bool global() const { return east - west >= 360; }
  double at(double lon, double lat) const {
    return base + amp * std::sin(kx * (lon - west)) * std::cos(ky * (lat - south));
  }
  int columns() const { return int(std::lround((east - west) / source)); }
  int rows() const { return int(std::lround((north - south) / source)); }
  // Bilinear between the written pixels' centres (float32, as stored),
  // clamped at the outermost centres: the plain resampling of the source.
  double bilinear(double lon, double lat) const {
    auto pixel = [&](int x, int y) {
      return double(float(at(west + (x + 0.5) * source, north - (y + 0.5) * source)));
    };
    const double c = std::clamp((lon - west) / source - 0.5, 0.0, columns() - 1.0);
    const double r = std::clamp((north - lat) / source - 0.5, 0.0, rows() - 1.0);
    const int c0 = std::min(int(c), columns() - 2), r0 = std::min(int(r), rows() - 2);
    const double a = c - c0, b = r - r0;
    return (1 - b) * ((1 - a) * pixel(c0, r0) + a * pixel(c0 + 1, r0)) +
           b * ((1 - a) * pixel(c0, r0 + 1) + a * pixel(c0 + 1, r0 + 1));
  }
  void write(const std::string& path) const {
    const double gt[6] = {west, source, 0, north, 0, -source};
    write_dem(
        path, int(std::lround((east - west) / source)), int(std::lround((north - south) / source)),
        gt, "EPSG:4326", GDT_Float32,
        [&](int x, int y) { return at(west + (x + 0.5) * source, north - (y + 0.5) * source); });
  }
};
// 10..14 E, 45..48 N at 1/128 degree, waves of 2 by 1.5 degrees.
inline constexpr Surface kRegional{10,   14,  45,          48,           1.0 / 128,
                                   1200, 900, 2 * kPi / 2, 2 * kPi / 1.5};
// The whole globe at 1/4 degree, waves of 60 by 40 degrees: six across,
// continuous at 180 degrees. Its columns reach half a pixel past both sides
// of the antimeridian (1,441 of them, centred from 180 W to 180 E): the layout
// whose edges lie on +-180 instead, with no column centred on 180, is built
// wrong by the terrain builder next to 180 E (up to 7 m here; issue 39, part 1),
// which this test, written for the export, found at first.
inline constexpr Surface kGlobal{-180.125, 180.125, -90,          90,          0.25,
                                 1000,     800,     2 * kPi / 60, 2 * kPi / 40};

// Webmercator and geodetic packages of a surface, built once per test run.
inline fs::path surface_packages(const Surface& f, const std::string& tag) {
  return shared_folder("web-export-" + tag, [&](const fs::path& d) {
    f.write((d / "surface.tif").string());
    return run_all({tiler() + " terrain -q " + (d / "surface.tif").string() + " -o " +
                        (d / "mercator.mbtiles").string(),
                    tiler() + " terrain -q --tiling geodetic " + (d / "surface.tif").string() +
                        " -o " + (d / "geodetic.mbtiles").string()},
                   d);
  });
}

inline const fs::path& surface_dem() {
  static const fs::path dir = surface_packages(kRegional, "surface");
  return dir;
}

}  // namespace globe_test
