// The one wrapper around GDAL raster datasets: RAII handles, checked calls,
// errors that name the file and say what to do. GDAL's own messages are
// captured (not printed) and appended to ours.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <gdal.h>

namespace globe {

// Registers drivers, silences GDAL's own stderr printing and bounds its block
// cache (cache_mb). Idempotent.
void gdal_init(int cache_mb = 32);
// GDAL's last error message on this thread ("" if none).
std::string gdal_last_error();
// Checks the result of a GDAL/OGR call that returns CPLErr or OGRErr (0 = none):
// otherwise throws OutputError "`what` failed (GDAL's message)". Every call
// whose result matters goes through it (docs/architecture.md rule 3).
void gdal_check(int err, const std::string& what);

class SpatialRef;

// How a band's min/max is found: from overviews or a sample, or every pixel.
enum class Scan { kApproximate, kExact };

class GdalDataset {
 public:
  GdalDataset() = default;
  explicit GdalDataset(GDALDatasetH h, std::string name) : h_(h), name_(std::move(name)) {}
  ~GdalDataset();
  GdalDataset(GdalDataset&& o) noexcept : h_(o.h_), name_(std::move(o.name_)) { o.h_ = nullptr; }
  GdalDataset& operator=(GdalDataset&& o) noexcept;

  // Opens a raster read-only; throws InputError naming the file.
  static GdalDataset open_raster(const std::string& path);
  // Opens vector data (any OGR source) read-only; throws InputError naming the
  // file. A shapefile must come with its .shx and .dbf. CSV files get their
  // columns' types detected (numbers as numbers).
  static GdalDataset open_vector(const std::string& path);
  // A CSV file whose points are in the columns `x_column` and `y_column`
  // (types of the other columns detected; a layer without point geometry if
  // the columns are missing); throws InputError naming the file if it is not
  // a CSV file.
  // `option` names the option that asked for it, for messages. A column may
  // be a comma-separated list of candidate names (wildcards allowed).
  static GdalDataset open_csv_points(const std::string& path, const std::string& x_column,
                                     const std::string& y_column,
                                     const std::string& option = "--xy");
  // Creates a vector dataset with the driver GDAL guesses from the extension
  // (GPKG if none); throws OutputError.
  static GdalDataset create_vector(const std::string& path);

  // Creates a raster with `driver` ("GTiff", "MEM", ...) and creation options
  // ("KEY=VALUE"); throws OutputError naming `path`.
  static GdalDataset create_raster(const std::string& driver, const std::string& path, int width,
                                   int height, int bands, GDALDataType type,
                                   const std::vector<std::string>& options = {});
  // An in-memory VRT copy of `in` whose georeferencing and band settings can
  // be changed without touching the file; `name` is used in messages.
  static GdalDataset vrt_copy(GDALDatasetH in, const std::string& name);
  // An in-memory VRT of `width` columns whose column k is `in`'s column
  // (first + k) mod `period` (its first `period` columns repeat): a grid that
  // goes once around the Earth,
  // extended periodically (so that a kernel across the antimeridian finds
  // both neighbours). Georeferencing is left to the caller; band types,
  // colour interpretations and nodata are kept.
  // (A mask band of `in`'s own, not alpha or nodata, is not carried: the
  // caller checks has_mask_band first.)
  static GdalDataset periodic_columns_vrt(GDALDatasetH in, int first, int period, int width,
                                          const std::string& name);
  // Whether `in` has a mask band of its own (a .msk file, an internal mask),
  // not one derived from alpha or nodata.
  static bool has_mask_band(GDALDatasetH in);
  // gdal_translate into an in-memory VRT, `args` as the program's options.
  GdalDataset translate_to_vrt(const std::vector<std::string>& args) const;

  GDALDatasetH get() const { return h_; }
  const std::string& name() const { return name_; }
  int width() const { return GDALGetRasterXSize(h_); }
  int height() const { return GDALGetRasterYSize(h_); }
  int bands() const { return GDALGetRasterCount(h_); }
  GDALRasterBandH band(int i) const { return GDALGetRasterBand(h_, i); }
  std::optional<std::array<double, 6>> geotransform() const;
  std::string crs_wkt() const;  // "" if the dataset has no CRS
  std::optional<double> nodata(int band_index) const;
  GDALDataType data_type(int band_index) const;
  bool integer_type(int band_index) const;  // not floating point, not complex
  GDALColorInterp colour(int band_index) const;
  // For a palette band with a colour table: whether an entry is translucent.
  // nullopt for any other band.
  std::optional<bool> palette_translucent(int band_index) const;
  // Min and max of a band (nodata excluded). nullopt if GDAL cannot compute
  // them (then gdal_last_error() says why: no valid sample, or a read error).
  std::optional<std::array<double, 2>> min_max(int band_index, Scan scan) const;
  // Reads `rows` whole rows from row `y` as float64; throws InputError
  // naming the file and the row.
  void read_rows(int band_index, int y, int rows, double* out) const;
  // The whole band shrunk to out_w x out_h pixels (nearest neighbour; from
  // the file's overviews when it has them), as float64; throws InputError.
  void read_shrunk(int band_index, int out_w, int out_h, double* out) const;

  // Setters and writes: each checks GDAL's result and throws OutputError
  // naming the dataset and what it was setting.
  void set_geotransform(const std::array<double, 6>& gt);
  void set_crs(const SpatialRef& crs);
  void set_nodata(int band_index, double value);
  void set_colour(int band_index, GDALColorInterp colour);
  void fill(int band_index, double value);
  void write(int band_index, int x, int y, int w, int h, const void* data, GDALDataType type);
  // Closes (flushing what was written); the object is then empty.
  void close();

 private:
  GDALDatasetH h_ = nullptr;
  std::string name_;
};

}  // namespace globe
