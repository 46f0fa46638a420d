// Terrain tiles from the DEM mosaic (see tile_warper.hpp).
#include "terrain/tile_warper.hpp"

#include <cmath>
#include <limits>

#include "geo/spatial_ref.hpp"
#include "runtime/errors.hpp"

namespace globe {

TileWarper::TileWarper(const DemPlan& plan, const std::string& resampling) : plan_(plan) {
  std::vector<GdalDataset> sources;
  for (const auto& src : plan.sources) {
    opened_.push_back(GdalDataset::open_raster(src.path));
    const GDALDatasetH in = opened_.back().get();
    for (double shift : warp_shifts(src))
      sources.push_back(georeferenced_copy(in, src, shift, src.nodata, {1}));
  }
  WarpSpec spec;
  spec.target_crs = plan.tiling.crs;
  spec.resampling = resampling;
  spec.bands = 1;
  spec.type = plan.warp_single ? GDT_Float32 : GDT_Float64;
  spec.max_width = spec.max_height = plan.steps * kMaxGroup + 1;
  warper_ = std::make_unique<RasterWarper>(
      std::move(sources), std::move(spec),
      plan.sources[0].path + (plan.sources.size() > 1 ? " (or another input)" : ""));
}

OwnedSamples owned_samples(const tileformat::Tiling& tiling, tileformat::TileId id, int steps) {
  const bool last_x = id.x + 1 == tiling.tiles_x(id.z) && !tiling.wraps_x();
  const bool last_y = id.y + 1 == tiling.tiles_y(id.z);
  return {steps + (last_x ? 1 : 0), steps + (last_y ? 1 : 0)};
}

void TileWarper::warp(tileformat::TileId first, int cols, int rows, Window& out) {
  if (cols < 1 || rows < 1 || cols > kMaxGroup || rows > kMaxGroup)
    throw std::invalid_argument("TileWarper: group of " + std::to_string(cols) + " x " +
                                std::to_string(rows) + " tiles");
  const int n = plan_.steps;
  const tileformat::TileId last{first.z, first.x + cols - 1, first.y + rows - 1};
  const OwnedSamples corner = owned_samples(plan_.tiling, last, n);
  out.width = n * (cols - 1) + corner.cols;
  out.height = n * (rows - 1) + corner.rows;
  const double sp = plan_.tiling.sample_spacing(first.z, n);
  const tileformat::Bounds b = plan_.tiling.tile_bounds(first);
  // Pixel centres on the samples: the first centre is the tile's corner.
  const std::array<double, 6> gt = {b.min_x - sp / 2, sp, 0, b.max_y + sp / 2, 0, -sp};
  const size_t samples = size_t(out.width) * out.height;
  if (plan_.warp_single) {
    out.heights.clear();
    out.single.assign(samples, std::numeric_limits<float>::quiet_NaN());
    warper_->warp(gt, out.width, out.height, "tile " + first.str(), out.single.data());
  } else {
    out.single.clear();
    out.heights.assign(samples, std::numeric_limits<double>::quiet_NaN());
    warper_->warp(gt, out.width, out.height, "tile " + first.str(), out.heights.data());
  }
}

}  // namespace globe
