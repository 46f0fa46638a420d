// GDAL dataset wrapper (see gdal_dataset.hpp).
#include "geo/gdal_dataset.hpp"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal_utils.h>
#include <gdal_vrt.h>
#include <ogr_srs_api.h>

#include <cctype>
#include <filesystem>
#include <mutex>

#include "geo/spatial_ref.hpp"
#include "runtime/errors.hpp"

namespace globe {

void gdal_init(int cache_mb) {
  static std::once_flag once;
  std::call_once(once, [cache_mb] {
    GDALAllRegister();
    CPLSetErrorHandler(CPLQuietErrorHandler);
    GDALSetCacheMax64(static_cast<GIntBig>(cache_mb) * 1024 * 1024);
    CPLSetConfigOption("GDAL_PAM_ENABLED", "NO");  // never write .aux.xml next to inputs
    // Some drivers (JPEG in GDAL 3.6) build their creation option list on
    // its first request, and two threads' first CreateCopy can both build it:
    // one frees the string the other is parsing (ASan caught it, merging
    // imagery; OSGeo/gdal#12389). Built once here, before any thread uses it.
    for (const char* name : {"JPEG", "WEBP", "PNG", "GTiff"})
      if (GDALDriverH d = GDALGetDriverByName(name))
        GDALGetMetadataItem(d, GDAL_DMD_CREATIONOPTIONLIST, nullptr);
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

GDALDataType GdalDataset::data_type(int band_index) const {
  return GDALGetRasterDataType(band(band_index));
}

bool GdalDataset::integer_type(int band_index) const {
  const GDALDataType type = data_type(band_index);
  return !GDALDataTypeIsFloating(type) && !GDALDataTypeIsComplex(type);
}

GDALColorInterp GdalDataset::colour(int band_index) const {
  return GDALGetRasterColorInterpretation(band(band_index));
}

std::optional<bool> GdalDataset::palette_translucent(int band_index) const {
  GDALRasterBandH b = band(band_index);
  GDALColorTableH table = GDALGetRasterColorTable(b);
  if (GDALGetRasterColorInterpretation(b) != GCI_PaletteIndex || !table) return std::nullopt;
  for (int i = 0; i < GDALGetColorEntryCount(table); ++i)
    if (GDALGetColorEntry(table, i)->c4 < 255) return true;
  return false;
}

std::optional<std::array<double, 2>> GdalDataset::min_max(int band_index, Scan scan) const {
  std::array<double, 2> mm{};
  CPLErrorReset();
  if (GDALComputeRasterMinMax(band(band_index), scan == Scan::kApproximate, mm.data()) != CE_None)
    return std::nullopt;
  return mm;
}

void GdalDataset::read_rows(int band_index, int y, int rows, double* out) const {
  const int w = width();
  if (GDALRasterIO(band(band_index), GF_Read, 0, y, w, rows, out, w, rows, GDT_Float64, 0, 0) !=
      CE_None)
    throw InputError(name_ + ": cannot read row " + std::to_string(y) + " (" + gdal_last_error() +
                     "); the file may be truncated or corrupt");
}

void GdalDataset::read_shrunk(int band_index, int out_w, int out_h, double* out) const {
  if (GDALRasterIO(band(band_index), GF_Read, 0, 0, width(), height(), out, out_w, out_h,
                   GDT_Float64, 0, 0) != CE_None)
    throw InputError(name_ + ": cannot read a " + std::to_string(out_w) + " x " +
                     std::to_string(out_h) + " overview (" + gdal_last_error() +
                     "); the file may be truncated or corrupt");
}

void GdalDataset::set_geotransform(const std::array<double, 6>& gt) {
  std::array<double, 6> copy = gt;
  gdal_check(GDALSetGeoTransform(h_, copy.data()), name_ + ": setting the geotransform");
}

void GdalDataset::set_crs(const SpatialRef& crs) {
  gdal_check(GDALSetSpatialRef(h_, crs.get()), name_ + ": setting the CRS");
}

void GdalDataset::set_nodata(int band_index, double value) {
  gdal_check(GDALSetRasterNoDataValue(band(band_index), value),
             name_ + ": setting band " + std::to_string(band_index) + "'s nodata value");
}

void GdalDataset::set_colour(int band_index, GDALColorInterp colour) {
  gdal_check(GDALSetRasterColorInterpretation(band(band_index), colour),
             name_ + ": setting band " + std::to_string(band_index) + "'s colour");
}

void GdalDataset::fill(int band_index, double value) {
  gdal_check(GDALFillRaster(band(band_index), value, 0),
             name_ + ": filling band " + std::to_string(band_index));
}

void GdalDataset::write(int band_index, int x, int y, int w, int h, const void* data,
                        GDALDataType type) {
  gdal_check(GDALRasterIO(band(band_index), GF_Write, x, y, w, h, const_cast<void*>(data), w, h,
                          type, 0, 0),
             name_ + ": writing pixels");
}

void GdalDataset::close() {
  if (h_) GDALClose(h_);
  h_ = nullptr;
}

GdalDataset GdalDataset::create_raster(const std::string& driver, const std::string& path,
                                       int width, int height, int bands, GDALDataType type,
                                       const std::vector<std::string>& options) {
  GDALDriverH d = GDALGetDriverByName(driver.c_str());
  if (!d) throw OutputError("GDAL has no " + driver + " driver");
  CPLStringList opts;
  for (const std::string& o : options)
    opts.AddString(o.c_str());
  CPLErrorReset();
  GDALDatasetH h = GDALCreate(d, path.c_str(), width, height, bands, type, opts.List());
  if (!h)
    throw OutputError(path + ": cannot create the " + driver + " raster (" + gdal_last_error() +
                      "); check the folder exists and is writable");
  return GdalDataset(h, path);
}

GdalDataset GdalDataset::vrt_copy(GDALDatasetH in, const std::string& name) {
  CPLErrorReset();
  GDALDatasetH h =
      GDALCreateCopy(GDALGetDriverByName("VRT"), "", in, FALSE, nullptr, nullptr, nullptr);
  if (!h) throw InputError(name + ": cannot wrap the raster (" + gdal_last_error() + ")");
  return GdalDataset(h, name);
}

GdalDataset GdalDataset::periodic_columns_vrt(GDALDatasetH in, int first, int period, int width,
                                              const std::string& name) {
  const int w = period, h = GDALGetRasterYSize(in);
  if (period < 1 || period > GDALGetRasterXSize(in) || first < 0 || first >= w || width < 1)
    throw std::logic_error("periodic_columns_vrt: columns out of range");
  CPLErrorReset();
  VRTDatasetH vrt = VRTCreate(width, h);
  if (!vrt) throw InputError(name + ": cannot wrap the raster (" + gdal_last_error() + ")");
  GdalDataset out(static_cast<GDALDatasetH>(vrt), name);
  for (int b = 1; b <= GDALGetRasterCount(in); ++b) {
    GDALRasterBandH src = GDALGetRasterBand(in, b);
    auto fail = [&] {
      return InputError(name + ": cannot wrap band " + std::to_string(b) + " (" +
                        gdal_last_error() + ")");
    };
    if (VRTAddBand(vrt, GDALGetRasterDataType(src), nullptr) != CE_None) throw fail();
    GDALRasterBandH dst = GDALGetRasterBand(out.get(), b);
    GDALSetRasterColorInterpretation(dst, GDALGetRasterColorInterpretation(src));
    int has_nodata = 0;
    const double nodata = GDALGetRasterNoDataValue(src, &has_nodata);
    if (has_nodata) GDALSetRasterNoDataValue(dst, nodata);
    // Runs of consecutive source columns, wrapping at the last.
    for (int x = 0, from = first; x < width; from = 0) {
      const int run = std::min(w - from, width - x);
      if (VRTAddSimpleSource(static_cast<VRTSourcedRasterBandH>(dst), src, from, 0, run, h, x, 0,
                             run, h, "near", VRT_NODATA_UNSET) != CE_None)
        throw fail();
      x += run;
    }
  }
  return out;
}

bool GdalDataset::has_mask_band(GDALDatasetH in) {
  for (int b = 1; b <= GDALGetRasterCount(in); ++b) {
    const int flags = GDALGetMaskFlags(GDALGetRasterBand(in, b));
    if (!(flags & (GMF_ALL_VALID | GMF_NODATA | GMF_ALPHA))) return true;
  }
  return false;
}

GdalDataset GdalDataset::translate_to_vrt(const std::vector<std::string>& args) const {
  CPLStringList argv;
  argv.AddString("-of");
  argv.AddString("VRT");
  for (const std::string& a : args)
    argv.AddString(a.c_str());
  GDALTranslateOptions* options = GDALTranslateOptionsNew(argv.List(), nullptr);
  if (!options) throw std::logic_error("gdal_translate options: " + gdal_last_error());
  int usage_error = 0;
  CPLErrorReset();
  GDALDatasetH out = GDALTranslate("", h_, options, &usage_error);
  GDALTranslateOptionsFree(options);
  if (!out) throw InputError(name_ + ": cannot select its bands (" + gdal_last_error() + ")");
  return GdalDataset(out, name_);
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
  const char* const csv_options[] = {"AUTODETECT_TYPE=YES", nullptr};
  const bool csv = ext == ".csv" || ext == ".tsv";
  GDALDatasetH h = GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr,
                              csv ? csv_options : nullptr, nullptr);
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

GdalDataset GdalDataset::open_csv_points(const std::string& path, const std::string& x_column,
                                         const std::string& y_column, const std::string& option) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path + ": no such file; check the path");
  const std::string x = "X_POSSIBLE_NAMES=" + x_column, y = "Y_POSSIBLE_NAMES=" + y_column;
  const char* const drivers[] = {"CSV", nullptr};
  const char* const options[] = {x.c_str(), y.c_str(), "AUTODETECT_TYPE=YES",
                                 "KEEP_GEOM_COLUMNS=NO", nullptr};
  CPLErrorReset();
  GDALDatasetH h =
      GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, drivers, options, nullptr);
  if (!h) {
    const std::string why = gdal_last_error();
    throw InputError(path + ": " + option + " reads CSV files and this is none" +
                     (why.empty() ? "" : " (" + why + ")") + "; without " + option +
                     ", any OGR point layer is read as it is");
  }
  return GdalDataset(h, path);
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
