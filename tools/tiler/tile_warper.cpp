// Terrain tiles from the DEM mosaic (see tile_warper.hpp).
#include "tile_warper.hpp"

#include <cmath>
#include <limits>

#include "errors.hpp"
#include "spatial_ref.hpp"

namespace globe {

TileWarper::TileWarper(const DemPlan& plan, const std::string& resampling) : plan_(plan) {
  GDALDriverH vrt = GDALGetDriverByName("VRT");
  std::vector<GdalDataset> sources;
  for (const auto& src : plan.sources) {
    opened_.push_back(GdalDataset::open_raster(src.path));
    const GdalDataset& in = opened_.back();
    for (double shift : src.x_shifts) {
      GDALDatasetH copy = GDALCreateCopy(vrt, "", in.get(), FALSE, nullptr, nullptr, nullptr);
      if (!copy)
        throw InputError(src.path + ": cannot wrap the raster (" + gdal_last_error() + ")");
      GdalDataset wrapped(copy, src.path);
      auto gt = src.geotransform;
      gt[0] += shift;
      GDALSetGeoTransform(copy, gt.data());
      SpatialRef crs = SpatialRef::from_wkt(src.crs_wkt, src.path);
      GDALSetSpatialRef(copy, crs.get());
      if (src.nodata) GDALSetRasterNoDataValue(wrapped.band(1), *src.nodata);
      sources.push_back(std::move(wrapped));
    }
  }
  WarpSpec spec;
  spec.tiling = plan.tiling;
  spec.resampling = resampling;
  spec.bands = 1;
  spec.type = GDT_Float64;
  spec.nan_nodata = true;
  spec.max_width = spec.max_height = plan.steps * kMaxGroup;
  // A real tile of the finest zoom, in the data.
  const auto range = plan.tiling.tiles_covering(plan.data_areas.front(), plan.max_zoom);
  const auto b = plan.tiling.tile_bounds(
      {plan.max_zoom, (range.min_x + range.max_x) / 2, (range.min_y + range.max_y) / 2});
  const double sp = plan.tiling.sample_spacing(plan.max_zoom, plan.steps);
  spec.initial_gt = {b.min_x - sp / 2, sp, 0, b.max_y + sp / 2, 0, -sp};
  warper_ = std::make_unique<RasterWarper>(
      std::move(sources), std::move(spec),
      plan.sources[0].path + (plan.sources.size() > 1 ? " (or another input)" : ""));
}

void TileWarper::warp(tileformat::TileId id, int cols, int rows, std::vector<double>& heights) {
  if (cols < 1 || rows < 1 || cols > kMaxGroup || rows > kMaxGroup)
    throw std::invalid_argument("TileWarper: group of " + std::to_string(cols) + " x " +
                                std::to_string(rows) + " tiles");
  const int w = plan_.steps * cols, h = plan_.steps * rows;
  const double sp = plan_.tiling.sample_spacing(id.z, plan_.steps);
  const tileformat::Bounds first = plan_.tiling.tile_bounds(id);
  // Pixel centres on the samples: the first centre is the tile's corner.
  const std::array<double, 6> gt = {first.min_x - sp / 2, sp, 0, first.max_y + sp / 2, 0, -sp};
  heights.assign(static_cast<size_t>(w) * h, std::numeric_limits<double>::quiet_NaN());
  warper_->warp(gt, w, h, "tile " + id.str(), heights.data());
}

}  // namespace globe
