// Small GeoTIFF fixtures made with GDAL inside the tests, and raster reading
// for comparisons. Each fixture says which property it is for.
#pragma once

#include <cpl_string.h>
#include <gdal.h>
#include <gdal_utils.h>
#include <ogr_srs_api.h>

#include "test_support.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

namespace globe_test {

struct Raster {
  int width = 0, height = 0;
  double gt[6] = {0, 1, 0, 0, 0, -1};
  std::vector<double> data;  // NaN where nodata
  std::string wkt;
  double at(int x, int y) const { return data[size_t(y) * width + x]; }
  size_t valid_count() const {
    size_t n = 0;
    for (double v : data)
      n += !std::isnan(v);
    return n;
  }
};

inline void gdal_setup() {
  static bool done = false;
  if (!done) {
    GDALAllRegister();
    CPLSetErrorHandler(CPLQuietErrorHandler);
    done = true;
  }
}

// Writes a one-band GeoTIFF; `height_at(x, y)` gives each pixel value.
inline void write_dem(const std::string& path, int w, int h, const double gt[6],
                      const std::string& srs, GDALDataType type,
                      const std::function<double(int, int)>& height_at,
                      const double* nodata = nullptr) {
  gdal_setup();
  GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), w, h, 1, type, nullptr);
  GDALSetGeoTransform(ds, const_cast<double*>(gt));
  if (!srs.empty()) {
    OGRSpatialReferenceH s = OSRNewSpatialReference(nullptr);
    OSRSetFromUserInput(s, srs.c_str());
    GDALSetSpatialRef(ds, s);
    OSRRelease(s);
  }
  GDALRasterBandH b = GDALGetRasterBand(ds, 1);
  if (nodata) GDALSetRasterNoDataValue(b, *nodata);
  std::vector<double> row(w);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x)
      row[x] = height_at(x, y);
    if (GDALRasterIO(b, GF_Write, 0, y, w, 1, row.data(), w, 1, GDT_Float64, 0, 0) != CE_None)
      break;
  }
  GDALClose(ds);
}

// The dataset's CRS as WKT ("" if none).
inline std::string crs_wkt(GDALDatasetH ds) {
  std::string out;
  if (auto s = GDALGetSpatialRef(ds)) {
    char* wkt = nullptr;
    OSRExportToWkt(s, &wkt);
    out = wkt ? wkt : "";
    CPLFree(wkt);
  }
  return out;
}

inline Raster read_raster(const std::string& path) {
  gdal_setup();
  Raster r;
  GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
  if (!ds) return r;
  r.width = GDALGetRasterXSize(ds);
  r.height = GDALGetRasterYSize(ds);
  GDALGetGeoTransform(ds, r.gt);
  r.wkt = crs_wkt(ds);
  GDALRasterBandH b = GDALGetRasterBand(ds, 1);
  r.data.resize(size_t(r.width) * r.height);
  if (GDALRasterIO(b, GF_Read, 0, 0, r.width, r.height, r.data.data(), r.width, r.height,
                   GDT_Float64, 0, 0) != CE_None)
    r.data.clear();
  int has = 0;
  const double nd = GDALGetRasterNoDataValue(b, &has);
  if (has && !std::isnan(nd))
    for (auto& v : r.data)
      if (v == nd) v = NAN;
  GDALClose(ds);
  return r;
}

// gdalwarp (the library call) of `src` onto exactly the grid of `like`.
// The independent reference for heights: the gdalwarp program, run as a
// user runs it, with exact reprojection (-et 0) and the same resampling,
// onto exactly the grid of `like` (an extracted zoom: pixel centres on the
// samples). `sources` in drawing order (later on top); `extra`: more
// gdalwarp options. Files go to `dir`.
inline Raster gdalwarp_reference(const std::vector<std::string>& sources, const Raster& like,
                                 const std::string& resampling, const fs::path& dir,
                                 const std::string& extra = "") {
  const fs::path crs = dir / "reference_crs.wkt", out = dir / "reference.tif";
  std::ofstream(crs) << like.wkt;
  std::string cmd = "gdalwarp -q -overwrite -et 0 -r " + resampling + " -t_srs " + crs.string() +
                    " -ot Float64 -dstnodata nan -te";
  for (double v : {like.gt[0], like.gt[3] + like.height * like.gt[5],
                   like.gt[0] + like.width * like.gt[1], like.gt[3]})
    cmd += CPLSPrintf(" %.17g", v);
  cmd += CPLSPrintf(" -ts %d %d ", like.width, like.height) + extra;
  for (const auto& s : sources)
    cmd += " " + s;
  const RunResult r = run(cmd + " " + out.string(), dir);
  EXPECT_EQ(r.exit_code, 0) << cmd << "\n" << r.err;
  return read_raster(out.string());
}

// Our heights against a reference where both have data.
struct HeightComparison {
  size_t compared = 0, reference_valid = 0, only_ours = 0, only_reference = 0;
  double max_diff = 0, p999 = 0;  // metres
};

inline HeightComparison compare_heights(const Raster& ours, const Raster& ref) {
  HeightComparison c;
  std::vector<double> diffs;
  for (size_t i = 0; i < ours.data.size() && i < ref.data.size(); ++i) {
    const double a = ours.data[i], b = ref.data[i];
    if (!std::isnan(b)) ++c.reference_valid;
    if (std::isnan(a) || std::isnan(b)) {
      c.only_ours += !std::isnan(a) && std::isnan(b);
      c.only_reference += std::isnan(a) && !std::isnan(b);
      continue;
    }
    diffs.push_back(std::abs(a - b));
  }
  c.compared = diffs.size();
  if (diffs.empty()) return c;
  const size_t k = std::min(diffs.size() - 1, static_cast<size_t>(0.999 * diffs.size()));
  std::nth_element(diffs.begin(), diffs.begin() + static_cast<ptrdiff_t>(k), diffs.end());
  c.p999 = diffs[k];
  c.max_diff = *std::max_element(diffs.begin(), diffs.end());
  return c;
}

}  // namespace globe_test
