// Warps a mosaic of raster sources onto windows of a pixel grid in the tiling
// CRS, for the terrain and the imagery builders: what `gdalwarp -et 0` would
// write into the same pixels of a grid that holds the window (docs/terrain.md
// "Warping"). One RasterWarper per worker thread: GDAL handles are not shared
// between threads.
//
// GDAL's warp kernel (the engine behind gdalwarp) does the resampling, with
// three things decided here instead of by GDAL's per-window heuristics, which
// go wrong for global data (a window at the antimeridian or a pole made GDAL
// read the whole source row and widen the resampling kernel as if
// downsampling):
//   - the source coordinates of every destination pixel centre, exact to
//     within `tolerance_px` (WindowCoordinates);
//   - the source window: exactly the pixels the kernel can reach;
//   - the kernel's scale: source pixels per destination pixel around the
//     window, not the ratio of the two windows' sizes.
// Sources come wrapped (VRTs) by the caller, carrying their resolved CRS,
// nodata values, +-360 degree shifts and, for imagery, an alpha band (the
// last band, colour interpretation alpha). Later sources are drawn on top.
#pragma once

#include <gdal.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "geo/gdal_dataset.hpp"

namespace globe {

// The resampling names GDAL's warper knows, as listed in --help and errors.
extern const char* const kResamplingNames;
bool is_resampling(const std::string& name);

// Largest error of the interpolated reprojection, in source pixels: heights
// move by at most this times the steepest step between two source samples
// (1e-7 px x 3 km = 0.3 mm; 1e-5 px let 0.1 % of a 1 cm-step global grid's
// samples round to the other quantum than gdalwarp -et 0 gives). Cubic
// interpolation keeps the cost far below one PROJ call per pixel.
inline constexpr double kDefaultTransformTolerancePx = 1e-7;

struct WarpSpec {
  std::string target_crs;  // CRS of the destination grid (WKT)
  std::string resampling = "bilinear";
  int bands = 1;                    // destination bands, the alpha band (if any) last
  bool alpha = false;               // the last band receives coverage (0 none .. 255 full)
  GDALDataType type = GDT_Float64;  // destination and working type
  int max_width = 0, max_height = 0;
  double tolerance_px = kDefaultTransformTolerancePx;
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
  // Throws InputError naming the inputs and `what` (e.g. the tile) when a
  // source cannot be read.
  void warp(const std::array<double, 6>& gt, int w, int h, const std::string& what, void* data);

  struct Source;  // one source's transformer and warp options

 private:
  void warp_source(Source& src, int w, int h, const std::string& what, void* data);

  std::vector<GdalDataset> datasets_;
  std::vector<std::unique_ptr<Source>> sources_;
  WarpSpec spec_;
  std::string inputs_;
};

}  // namespace globe
