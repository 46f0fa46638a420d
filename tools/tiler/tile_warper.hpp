// Warps the DEM mosaic onto terrain tiles' sample grids (one TileWarper per
// worker thread). Each source is opened through a VRT that carries its
// resolved CRS, nodata value and longitude shift (+-360 copies for data past
// the antimeridian); the warping itself is RasterWarper's.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "dem_plan.hpp"
#include "raster_warper.hpp"
#include "tileformat/tile_id.hpp"

namespace globe {

class TileWarper {
 public:
  TileWarper(const DemPlan& plan, const std::string& resampling);

  // Heights of the steps^2 samples the tile owns (its last column and row
  // belong to the east/south neighbours), row-major from the north-west
  // corner; NaN where no input has data. Not warping the shared samples also
  // keeps the destination window off the antimeridian, where GDAL's source
  // window computation wraps. Throws InputError on read failures.
  // The same for a block of cols x rows tiles whose north-west tile is
  // `first`, in one warp call (less per-call overhead): the result is
  // (cols * steps) x (rows * steps) samples. cols, rows <= kMaxGroup.
  void warp(tileformat::TileId first, int cols, int rows, std::vector<double>& heights);
  void warp(tileformat::TileId id, std::vector<double>& heights) { warp(id, 1, 1, heights); }
  static constexpr int kMaxGroup = 4;

 private:
  const DemPlan& plan_;
  std::vector<GdalDataset> opened_;  // the inputs; must outlive the wrappers
  std::unique_ptr<RasterWarper> warper_;
};

}  // namespace globe
