// GDAL dataset wrapper (see gdal_dataset.hpp).
#include "gdal_dataset.hpp"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <ogr_srs_api.h>

#include <cctype>
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

void gdal_check(int err, const std::string& what) {
  if (err != 0) throw OutputError(what + " failed (" + gdal_last_error() + ")");
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

namespace globe {
namespace {

bool sibling_exists(const std::filesystem::path& shp, const char* lower, const char* upper) {
  std::error_code ec;
  auto p = shp;
  if (std::filesystem::exists(p.replace_extension(lower), ec)) return true;
  return std::filesystem::exists(p.replace_extension(upper), ec);
}

}  // namespace

GdalDataset GdalDataset::open_vector(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const bool virtual_path = path.rfind("/vsi", 0) == 0;
  if (!virtual_path && !fs::exists(path, ec))
    throw InputError(path + ": no such file; check the path");
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (!virtual_path && ext == ".shp") {
    if (!sibling_exists(path, ".shx", ".SHX"))
      throw InputError(path +
                       ": the shapefile's index (.shx) is missing; copy it next to the .shp");
    if (!sibling_exists(path, ".dbf", ".DBF"))
      throw InputError(path +
                       ": the shapefile's attribute table (.dbf) is missing; copy it next to the "
                       ".shp");
  }
  CPLErrorReset();
  GDALDatasetH h =
      GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr);
  if (!h) {
    std::string why = gdal_last_error();
    throw InputError(path + ": not vector data GDAL/OGR can read" +
                     (why.empty() ? "" : " (" + why + ")") +
                     "; pass a Shapefile, GeoPackage, GeoJSON or another OGR format");
  }
  GdalDataset ds(h, path);
  if (GDALDatasetGetLayerCount(h) < 1) throw InputError(path + ": no vector layers");
  return ds;
}

GdalDataset GdalDataset::create_vector(const std::string& path) {
  namespace fs = std::filesystem;
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const char* name = "GPKG";
  if (ext == ".shp")
    name = "ESRI Shapefile";
  else if (ext == ".geojson" || ext == ".json")
    name = "GeoJSON";
  else if (ext == ".fgb")
    name = "FlatGeobuf";
  else if (ext == ".csv")
    name = "CSV";
  GDALDriverH driver = GDALGetDriverByName(name);
  if (!driver) throw OutputError(std::string("GDAL has no ") + name + " driver");
  CPLErrorReset();
  GDALDatasetH h = GDALCreate(driver, path.c_str(), 0, 0, 0, GDT_Unknown, nullptr);
  if (!h)
    throw OutputError(path + ": cannot create (" + gdal_last_error() +
                      "); check the folder exists and is writable");
  return GdalDataset(h, path);
}

}  // namespace globe
