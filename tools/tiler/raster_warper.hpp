// Warps a mosaic of raster sources onto windows of a pixel grid in the tiling
// CRS, for the terrain and the imagery builders. One RasterWarper per worker
// thread: GDAL handles are not shared between threads. GDAL's warp operation
// (the engine behind gdalwarp) is created once per source and reused for
// every window: only the destination geotransform changes, and GDAL reads
// only the source window it needs, so memory does not depend on input size.
//
// Sources come wrapped (VRTs) by the caller, carrying their resolved CRS,
// nodata values, +-360 degree shifts and, for imagery, an alpha band (the
// last band, colour interpretation alpha). Later sources are drawn on top.
#pragma once

#include <gdal.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "gdal_dataset.hpp"
#include "spatial_ref.hpp"
#include "tileformat/tiling.hpp"

namespace globe {

// The resampling names GDAL's warper knows, as listed in --help and errors.
extern const char* const kResamplingNames;
bool is_resampling(const std::string& name);

struct WarpSpec {
  tileformat::Tiling tiling;
  std::string resampling = "bilinear";
  int bands = 1;                    // destination bands, the alpha band (if any) last
  bool alpha = false;               // the last band receives coverage (0 none .. 255 full)
  GDALDataType type = GDT_Float64;  // destination and working type
  bool nan_nodata = false;          // float destination: NaN marks pixels without data
  int max_width = 0, max_height = 0;
  double error_threshold = 0.125;  // approximation error in pixels (gdalwarp -et)
  // A real window of the finest zoom: GDAL derives transformer settings (e.g.
  // longitude wrapping) from the destination extent when they are created.
  std::array<double, 6> initial_gt{};
};

class RasterWarper {
 public:
  // `inputs` names the inputs in error messages.
  RasterWarper(std::vector<GdalDataset> sources, WarpSpec spec, std::string inputs);
  ~RasterWarper();
  RasterWarper(const RasterWarper&) = delete;
  RasterWarper& operator=(const RasterWarper&) = delete;

  // Warps onto the w x h window with geotransform `gt`. `data` holds
  // spec.bands planes of w * h values of spec.type (band-sequential, rows from
  // the north); what it holds on entry is the background that sources cover.
  // Windows at the antimeridian of webmercator are warped in a Mercator
  // centred on them (GDAL's source window computation breaks at the wrap).
  // Throws InputError naming the inputs and `what` (e.g. the tile).
  void warp(const std::array<double, 6>& gt, int w, int h, const std::string& what, void* data);

  struct Operation;  // one source's transformer + warp operation

 private:
  std::vector<std::unique_ptr<Operation>> make_operations();
  void io(GDALRWFlag flag, int w, int h, void* data, const std::string& what);

  std::vector<GdalDataset> sources_;
  WarpSpec spec_;
  std::string inputs_;
  SpatialRef target_;  // the tiling CRS
  GdalDataset dest_;
};

}  // namespace globe
