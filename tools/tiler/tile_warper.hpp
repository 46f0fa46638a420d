// Warps the source mosaic onto one tile's sample grid. One TileWarper per
// worker thread: GDAL handles are not shared between threads. Each source is
// opened through a VRT that carries its resolved CRS, nodata value and
// longitude shift (+-360 copies for data past the antimeridian). GDAL's warp
// operation (the engine behind gdalwarp) is created once per source and
// reused for every tile: only the destination geotransform changes, and GDAL
// reads only the source window the tile needs.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "dem_plan.hpp"
#include "gdal_dataset.hpp"
#include "tileformat/tile_id.hpp"

namespace globe {

class TileWarper {
 public:
  TileWarper(const DemPlan& plan, const std::string& resampling);
  ~TileWarper();
  TileWarper(const TileWarper&) = delete;
  TileWarper& operator=(const TileWarper&) = delete;

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

  struct Operation;  // one source's transformer + warp operation

 private:
  std::vector<std::unique_ptr<Operation>> make_operations();
  const DemPlan& plan_;
  std::string resampling_;
  std::vector<GdalDataset> opened_;   // the inputs; must outlive the wrappers below
  std::vector<GdalDataset> sources_;  // VRT wrappers, one per source and shift
  GdalDataset dest_;
  std::vector<std::unique_ptr<Operation>> operations_;  // for the tiling CRS
};

}  // namespace globe
