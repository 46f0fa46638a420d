// Warps the DEM mosaic onto terrain tiles' sample grids (one TileWarper per
// worker thread). Each source is opened through a VRT that carries its
// resolved CRS, nodata value and longitude shift (+-360 copies for data past
// the antimeridian); the warping itself is RasterWarper's.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "raster/raster_warper.hpp"
#include "terrain/dem_plan.hpp"
#include "tileformat/tile_id.hpp"

namespace globe {

// The samples a tile warps itself: steps x steps from its north-west
// corner, plus the last column / row where no east / south neighbour in the
// tiling owns them (the south edge of every scheme, the east edge of a local
// tiling; global tilings wrap around in x).
struct OwnedSamples {
  int cols = 0, rows = 0;
};
OwnedSamples owned_samples(const tileformat::Tiling& tiling, tileformat::TileId id, int steps);

class TileWarper {
 public:
  TileWarper(const DemPlan& plan, const std::string& resampling);

  // The heights a block of cols x rows tiles (north-west tile `first`)
  // owns, warped in one call (less per-call overhead): row-major from the
  // north-west corner, `width` x `height` samples; NaN where no input has
  // data. Each sample is warped by exactly one tile, so samples shared by
  // neighbours cannot round to two different quanta. cols, rows <=
  // kMaxGroup. Throws InputError on read failures.
  // Heights in the plan's working precision (plan.warp_single: `single`,
  // else `heights`).
  struct Window {
    int width = 0, height = 0;
    std::vector<double> heights;
    std::vector<float> single;
    double at(size_t i) const { return single.empty() ? heights[i] : single[i]; }
  };
  void warp(tileformat::TileId first, int cols, int rows, Window& out);
  static constexpr int kMaxGroup = 4;

 private:
  const DemPlan& plan_;
  std::vector<GdalDataset> opened_;  // the inputs; must outlive the wrappers
  std::unique_ptr<RasterWarper> warper_;
};

}  // namespace globe
