// GDAL dataset wrapper (see gdal_dataset.hpp).
#include "gdal_dataset.hpp"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <ogr_srs_api.h>

#include <filesystem>
#include <mutex>

#include "errors.hpp"

namespace globe {

void gdal_init(int cache_mb) {
  static std::once_flag once;
  std::call_once(once, [cache_mb] {
    GDALAllRegister();
    CPLSetErrorHandler(CPLQuietErrorHandler);
    GDALSetCacheMax64(static_cast<GIntBig>(cache_mb) * 1024 * 1024);
    CPLSetConfigOption("GDAL_PAM_ENABLED", "NO");  // never write .aux.xml next to inputs
  });
}

std::string gdal_last_error() {
  const char* msg = CPLGetLastErrorMsg();
  return msg ? msg : "";
}

GdalDataset::~GdalDataset() {
  if (h_) GDALClose(h_);
}

GdalDataset& GdalDataset::operator=(GdalDataset&& o) noexcept {
  if (this != &o) {
    if (h_) GDALClose(h_);
    h_ = o.h_;
    name_ = std::move(o.name_);
    o.h_ = nullptr;
  }
  return *this;
}

GdalDataset GdalDataset::open_raster(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const bool virtual_path = path.rfind("/vsi", 0) == 0;
  if (!virtual_path && !fs::exists(path, ec))
    throw InputError(path + ": no such file; check the path");
  CPLErrorReset();
  GDALDatasetH h =
      GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr);
  if (!h) {
    std::string why = gdal_last_error();
    throw InputError(path + ": not a raster GDAL can read" + (why.empty() ? "" : " (" + why + ")") +
                     "; pass a GeoTIFF or another GDAL raster format");
  }
  GdalDataset ds(h, path);
  if (ds.bands() < 1) throw InputError(path + ": the raster has no bands");
  return ds;
}

std::optional<std::array<double, 6>> GdalDataset::geotransform() const {
  std::array<double, 6> gt{};
  if (GDALGetGeoTransform(h_, gt.data()) != CE_None) return std::nullopt;
  if (gt[1] == 0 || gt[5] == 0) return std::nullopt;
  return gt;
}

std::string GdalDataset::crs_wkt() const {
  OGRSpatialReferenceH srs = GDALGetSpatialRef(h_);
  if (!srs) return "";
  char* wkt = nullptr;
  const char* opts[] = {"FORMAT=WKT2_2018", nullptr};
  if (OSRExportToWktEx(srs, &wkt, opts) != OGRERR_NONE) {
    CPLFree(wkt);
    return "";
  }
  std::string out = wkt ? wkt : "";
  CPLFree(wkt);
  return out;
}

std::optional<double> GdalDataset::nodata(int band_index) const {
  int has = 0;
  double v = GDALGetRasterNoDataValue(band(band_index), &has);
  if (!has) return std::nullopt;
  return v;
}

}  // namespace globe
