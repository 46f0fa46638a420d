// Small GeoTIFF fixtures made with GDAL inside the tests, and raster reading
// for comparisons. Each fixture says which property it is for.
#pragma once

#include <cpl_string.h>
#include <gdal.h>
#include <gdal_utils.h>
#include <ogr_srs_api.h>

#include <cmath>
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
inline Raster warp_like(const std::string& src, const Raster& like, const std::string& resampling,
                        const std::string& out_path) {
  gdal_setup();
  CPLStringList args;
  for (const char* a : {"-of", "GTiff", "-ot", "Float64", "-dstnodata", "nan", "-r"})
    args.AddString(a);
  args.AddString(resampling.c_str());
  args.AddString("-t_srs");
  args.AddString(like.wkt.c_str());
  args.AddString("-te");
  for (double v : {like.gt[0], like.gt[3] + like.height * like.gt[5],
                   like.gt[0] + like.width * like.gt[1], like.gt[3]})
    args.AddString(CPLSPrintf("%.17g", v));
  args.AddString("-ts");
  args.AddString(CPLSPrintf("%d", like.width));
  args.AddString(CPLSPrintf("%d", like.height));
  GDALWarpAppOptions* opts = GDALWarpAppOptionsNew(args.List(), nullptr);
  GDALDatasetH in = GDALOpen(src.c_str(), GA_ReadOnly);
  GDALDatasetH out = GDALWarp(out_path.c_str(), nullptr, 1, &in, opts, nullptr);
  GDALWarpAppOptionsFree(opts);
  if (out) GDALClose(out);
  GDALClose(in);
  return read_raster(out_path);
}

}  // namespace globe_test
