// Terrain build planning (see dem_plan.hpp, docs/terrain.md "Planning").
#include "terrain/dem_plan.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <vector>

#include "geo/gdal_dataset.hpp"
#include "geo/spatial_ref.hpp"
#include "raster/raster_warper.hpp"
#include "runtime/errors.hpp"
#include "tileformat/mblock.hpp"

namespace globe {
namespace {

// Band types whose every value single precision holds exactly.
bool exact_in_single(GDALDataType type) {
  return type == GDT_Byte || type == GDT_UInt16 || type == GDT_Int16 || type == GDT_Float32;
}

void check_settings(const TerrainSettings& s) {
  check_tiling_options(s, "");
  const int steps = s.block_size - 1;
  if (steps < 2 * s.lattice || steps > 4096 || (steps & (steps - 1)) != 0)
    throw UsageError("--block-size: " + std::to_string(s.block_size) +
                     " must be 2^k + 1 between 33 and 4097 (e.g. 65, 129, 257, 513)");
  if (!is_resampling(s.resampling))
    throw UsageError("--resampling: '" + s.resampling + "' is not one of " + kResamplingNames);
  if (s.precision && !(*s.precision > 0)) throw UsageError("--precision must be positive");
  if (s.min_zoom && s.max_zoom && *s.min_zoom > *s.max_zoom)
    throw UsageError("--min-zoom " + std::to_string(*s.min_zoom) + " is larger than --max-zoom " +
                     std::to_string(*s.max_zoom));
}

// Min and max over the finite samples that are not nodata (GDAL's own
// min/max is infinite as soon as one sample is), read row by row; both NaN
// when there is none.
std::array<double, 2> finite_min_max(const GdalDataset& ds, std::optional<double> nodata) {
  std::vector<double> row(static_cast<size_t>(ds.width()));
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (int y = 0; y < ds.height(); ++y) {
    ds.read_rows(1, y, 1, row.data());
    for (double v : row)
      if (std::isfinite(v) && !(nodata && v == *nodata)) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  return {std::isfinite(lo) ? lo : nan, std::isfinite(hi) ? hi : nan};
}

}  // namespace

DemPlan plan_terrain(const TerrainSettings& s) {
  check_settings(s);
  gdal_init();
  DemPlan plan;
  plan.steps = s.block_size - 1;
  std::optional<SpatialRef> s_srs;
  if (!s.s_srs.empty()) s_srs = SpatialRef::from_user_input(s.s_srs, "--s_srs");

  // 1. Inputs: CRS, georeferencing, nodata, value range.
  double min_h = std::numeric_limits<double>::infinity(), max_h = -min_h;
  bool all_integer = true, all_single = true;
  std::vector<RasterSource> rasters;
  for (const auto& path : s.inputs) {
    GdalDataset ds = GdalDataset::open_raster(path);
    rasters.push_back(describe_raster(ds, path, s_srs));
    DemSource src;
    src.nodata = s.nodata ? s.nodata : ds.nodata(1);
    src.integer_type = ds.integer_type(1);
    all_integer = all_integer && src.integer_type;
    all_single = all_single && exact_in_single(ds.data_type(1));

    if (s.nodata) ds.set_nodata(1, *s.nodata);  // this handle's statistics only
    std::optional<std::array<double, 2>> mm = ds.min_max(1, Scan::kApproximate);
    if (mm && (std::isinf((*mm)[0]) || std::isinf((*mm)[1])))
      mm = finite_min_max(ds, src.nodata);  // infinite heights are holes, like NaN
    if (!mm || !std::isfinite((*mm)[0]) || !std::isfinite((*mm)[1])) {
      const std::string why = gdal_last_error();
      if (!why.empty() && why.find("no valid") == std::string::npos &&
          why.find("nodata") == std::string::npos)
        throw InputError(path + ": cannot read the raster data (" + why +
                         "); the file may be truncated or corrupt");
      mm = ds.min_max(1, Scan::kExact);
      if (!mm || !std::isfinite((*mm)[0]))
        throw InputError(path + ": holds no valid data (every sample is nodata" +
                         (src.nodata ? " = " + std::to_string(*src.nodata) : std::string()) + ")");
    }
    min_h = std::min(min_h, (*mm)[0]);
    max_h = std::max(max_h, (*mm)[1]);
    plan.sources.push_back(std::move(src));
  }

  // 2. Height step on the global quantization grid.
  plan.step_m = s.precision ? *s.precision : (all_integer ? 1.0 : 0.01);
  const double max_abs = std::max(std::abs(min_h), std::abs(max_h));
  if (max_abs / plan.step_m >= tileformat::kMaxQuantum)
    throw InputError(rasters[0].path + ": heights up to " + std::to_string(max_abs) +
                     " m do not fit with --precision " + std::to_string(plan.step_m) +
                     "; use a larger --precision");
  plan.fill_q = static_cast<int32_t>(std::llround(min_h / plan.step_m));
  // Single precision rounds a height h by up to h * 2^-24. Below
  // step * 2^16 that is under 1/256 of a step, and stays under 1/64 where
  // the approximate statistics miss heights up to 4x larger: it moves a
  // sample across a rounding boundary only within that distance of it.
  plan.warp_single = all_single && max_abs <= std::ldexp(plan.step_m, 16);

  // 3. Tiling, data areas, resolution and zooms.
  static_cast<Footprint&>(plan) = plan_footprint(rasters, s, "", TileGrid{plan.steps, true});
  for (size_t i = 0; i < rasters.size(); ++i)
    static_cast<RasterSource&>(plan.sources[i]) = rasters[i];
  return plan;
}

}  // namespace globe
