// The one wrapper around GDAL raster datasets: RAII handles, checked calls,
// errors that name the file and say what to do. GDAL's own messages are
// captured (not printed) and appended to ours.
#pragma once

#include <array>
#include <optional>
#include <string>

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
  // file. A shapefile must come with its .shx and .dbf.
  static GdalDataset open_vector(const std::string& path);
  // Creates a vector dataset with the driver GDAL guesses from the extension
  // (GPKG if none); throws OutputError.
  static GdalDataset create_vector(const std::string& path);

  GDALDatasetH get() const { return h_; }
  const std::string& name() const { return name_; }
  int width() const { return GDALGetRasterXSize(h_); }
  int height() const { return GDALGetRasterYSize(h_); }
  int bands() const { return GDALGetRasterCount(h_); }
  GDALRasterBandH band(int i) const { return GDALGetRasterBand(h_, i); }
  std::optional<std::array<double, 6>> geotransform() const;
  std::string crs_wkt() const;  // "" if the dataset has no CRS
  std::optional<double> nodata(int band_index) const;

 private:
  GDALDatasetH h_ = nullptr;
  std::string name_;
};

}  // namespace globe
