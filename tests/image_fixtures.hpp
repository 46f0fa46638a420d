// Image comparisons for the imagery tests: reading every band of a raster as
// bytes, gdalwarp (the library call) of a source onto exactly another
// raster's grid with an alpha band, and PSNR over the pixels both cover.
#pragma once

#include <cpl_string.h>
#include <gdal.h>
#include <gdal_utils.h>
#include <ogr_srs_api.h>

#include <cmath>
#include <string>
#include <vector>

#include "raster_fixtures.hpp"

namespace globe_test {

struct Image {
  int width = 0, height = 0, bands = 0;
  double gt[6] = {0, 1, 0, 0, 0, -1};
  std::string wkt;
  std::vector<uint8_t> px;  // band-sequential
  uint8_t at(int b, int x, int y) const { return px[(size_t(b) * height + y) * width + x]; }
};

inline Image read_image(const std::string& path) {
  gdal_setup();
  Image im;
  GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
  if (!ds) return im;
  im.width = GDALGetRasterXSize(ds);
  im.height = GDALGetRasterYSize(ds);
  im.bands = GDALGetRasterCount(ds);
  GDALGetGeoTransform(ds, im.gt);
  im.wkt = crs_wkt(ds);
  im.px.resize(size_t(im.bands) * im.width * im.height);
  if (GDALDatasetRasterIO(ds, GF_Read, 0, 0, im.width, im.height, im.px.data(), im.width, im.height,
                          GDT_Byte, im.bands, nullptr, 0, 0, 0) != CE_None)
    im.px.clear();
  GDALClose(ds);
  return im;
}

// gdalwarp -dstalpha of `src` (optionally only `bands`, as gdal_translate -b)
// onto exactly the grid of `like`, in `t_srs` (default: like's CRS).
inline Image warp_image_like(const std::string& src, const Image& like,
                             const std::string& resampling, const std::string& out_path,
                             const std::vector<int>& bands = {}, double error_threshold = 0.125,
                             const std::string& t_srs = "") {
  gdal_setup();
  GDALDatasetH in = GDALOpen(src.c_str(), GA_ReadOnly);
  GDALDatasetH selected = nullptr;
  if (!bands.empty()) {
    CPLStringList t;
    t.AddString("-of");
    t.AddString("VRT");
    for (int b : bands) {
      t.AddString("-b");
      t.AddString(std::to_string(b).c_str());
    }
    GDALTranslateOptions* o = GDALTranslateOptionsNew(t.List(), nullptr);
    selected = GDALTranslate((out_path + ".vrt").c_str(), in, o, nullptr);
    GDALTranslateOptionsFree(o);
  }
  CPLStringList args;
  for (const char* a : {"-of", "GTiff", "-ot", "Byte", "-dstalpha", "-r"})
    args.AddString(a);
  args.AddString(resampling.c_str());
  args.AddString("-et");
  args.AddString(CPLSPrintf("%.17g", error_threshold));
  args.AddString("-t_srs");
  args.AddString(t_srs.empty() ? like.wkt.c_str() : t_srs.c_str());
  args.AddString("-te");
  for (double v : {like.gt[0], like.gt[3] + like.height * like.gt[5],
                   like.gt[0] + like.width * like.gt[1], like.gt[3]})
    args.AddString(CPLSPrintf("%.17g", v));
  args.AddString("-ts");
  args.AddString(CPLSPrintf("%d", like.width));
  args.AddString(CPLSPrintf("%d", like.height));
  GDALWarpAppOptions* opts = GDALWarpAppOptionsNew(args.List(), nullptr);
  GDALDatasetH source = selected ? selected : in;
  GDALDatasetH out = GDALWarp(out_path.c_str(), nullptr, 1, &source, opts, nullptr);
  GDALWarpAppOptionsFree(opts);
  if (out) GDALClose(out);
  if (selected) GDALClose(selected);
  GDALClose(in);
  return read_image(out_path);
}

struct ImageDiff {
  size_t compared = 0;          // pixels opaque in both
  size_t coverage_differs = 0;  // opaque in one, transparent in the other
  int max_diff = 0;
  double psnr = 0;  // over the colour bands of compared pixels (inf if equal)
};

// Compares the first `colour` bands of two images on the same grid, alpha last.
inline ImageDiff compare_images(const Image& a, const Image& b, int colour) {
  ImageDiff d;
  double sq = 0;
  const int aa = a.bands - 1, ba = b.bands - 1;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const bool oa = a.at(aa, x, y) == 255, ob = b.at(ba, x, y) == 255;
      const bool ta = a.at(aa, x, y) == 0, tb = b.at(ba, x, y) == 0;
      if ((oa && tb) || (ta && ob)) ++d.coverage_differs;
      if (!oa || !ob) continue;
      ++d.compared;
      for (int c = 0; c < colour; ++c) {
        const int diff = int(a.at(c, x, y)) - int(b.at(c, x, y));
        d.max_diff = std::max(d.max_diff, std::abs(diff));
        sq += double(diff) * diff;
      }
    }
  const double mse = d.compared ? sq / (double(d.compared) * colour) : 0;
  d.psnr = mse > 0 ? 10 * std::log10(255.0 * 255.0 / mse) : INFINITY;
  return d;
}

}  // namespace globe_test
