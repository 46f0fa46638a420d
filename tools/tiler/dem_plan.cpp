// Terrain build planning (see dem_plan.hpp, docs/terrain.md "Planning").
#include "dem_plan.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>

#include "errors.hpp"
#include "gdal_dataset.hpp"
#include "spatial_ref.hpp"
#include "tileformat/mblock.hpp"

namespace globe {
namespace {

using tileformat::Bounds;
using tileformat::Tiling;

constexpr double kMercatorMaxLat = 85.05112877980659;
constexpr double kEarthRadius = 6378137.0;
constexpr double kPi = 3.14159265358979323846;

const std::set<std::string> kResamplings = {
    "near", "bilinear", "cubic", "cubicspline", "lanczos", "average", "min", "max", "med", "mode"};

double mercator_y(double lat_deg) {
  const double lat = std::clamp(lat_deg, -kMercatorMaxLat, kMercatorMaxLat) * kPi / 180.0;
  return kEarthRadius * std::log(std::tan(kPi / 4 + lat / 2));
}
double mercator_x(double lon_deg) {
  return kEarthRadius * lon_deg * kPi / 180.0;
}

// Lon/lat rectangle -> tiling CRS for the global schemes; empty if outside.
std::optional<Bounds> lonlat_to_global(const std::string& scheme, Bounds ll) {
  ll.min_x = std::max(ll.min_x, -180.0);
  ll.max_x = std::min(ll.max_x, 180.0);
  const double lat_limit = scheme == "webmercator" ? kMercatorMaxLat : 90.0;
  ll.min_y = std::max(ll.min_y, -lat_limit);
  ll.max_y = std::min(ll.max_y, lat_limit);
  if (!(ll.min_x < ll.max_x && ll.min_y < ll.max_y)) return std::nullopt;
  if (scheme == "geodetic") return ll;
  return Bounds{mercator_x(ll.min_x), mercator_y(ll.min_y), mercator_x(ll.max_x),
                mercator_y(ll.max_y)};
}

void check_settings(const TerrainSettings& s) {
  if (s.tiling != "webmercator" && s.tiling != "geodetic" && s.tiling != "local")
    throw UsageError("--tiling: '" + s.tiling + "' is not one of webmercator, geodetic, local");
  if (!s.t_srs.empty() && s.tiling != "local")
    throw UsageError("--t_srs applies to --tiling local only (" + s.tiling + " has a fixed CRS)");
  const int steps = s.block_size - 1;
  if (steps < 2 * s.lattice || steps > 4096 || (steps & (steps - 1)) != 0)
    throw UsageError("--block-size: " + std::to_string(s.block_size) +
                     " must be 2^k + 1 between 33 and 4097 (e.g. 65, 129, 257, 513)");
  if (!kResamplings.count(s.resampling))
    throw UsageError("--resampling: '" + s.resampling +
                     "' is not one of near, bilinear, cubic, cubicspline, lanczos, average, min, "
                     "max, med, mode");
  if (s.precision && !(*s.precision > 0)) throw UsageError("--precision must be positive");
  if (s.min_zoom && s.max_zoom && *s.min_zoom > *s.max_zoom)
    throw UsageError("--min-zoom " + std::to_string(*s.min_zoom) + " is larger than --max-zoom " +
                     std::to_string(*s.max_zoom));
}

}  // namespace

DemPlan plan_terrain(const TerrainSettings& s) {
  check_settings(s);
  gdal_init();
  DemPlan plan;
  plan.steps = s.block_size - 1;
  const SpatialRef wgs84 = SpatialRef::from_user_input("EPSG:4326", "internal");
  std::optional<SpatialRef> s_srs;
  if (!s.s_srs.empty()) s_srs = SpatialRef::from_user_input(s.s_srs, "--s_srs");

  // 1. Inputs: CRS, georeferencing, nodata, value range.
  double min_h = std::numeric_limits<double>::infinity(), max_h = -min_h;
  bool all_integer = true;
  std::optional<SpatialRef> first_crs;
  for (const auto& path : s.inputs) {
    GdalDataset ds = GdalDataset::open_raster(path);
    DemSource src;
    src.path = path;
    src.width = ds.width();
    src.height = ds.height();
    auto gt = ds.geotransform();
    if (!gt)
      throw InputError(path +
                       ": no georeferencing (geotransform); add a world file or assign one with "
                       "gdal_translate -a_ullr");
    if ((*gt)[2] != 0 || (*gt)[4] != 0)
      throw InputError(path + ": rotated rasters are not supported; run gdalwarp on it first");
    src.geotransform = *gt;
    src.crs_wkt = s_srs ? s_srs->wkt2() : ds.crs_wkt();
    if (src.crs_wkt.empty()) throw InputError(path + ": no CRS found; pass --s_srs EPSG:xxxx");
    src.nodata = s.nodata ? s.nodata : ds.nodata(1);
    const GDALDataType type = GDALGetRasterDataType(ds.band(1));
    src.integer_type = !GDALDataTypeIsFloating(type) && !GDALDataTypeIsComplex(type);
    all_integer = all_integer && src.integer_type;
    std::error_code ec;
    src.file_bytes =
        std::filesystem::is_regular_file(path, ec) ? std::filesystem::file_size(path, ec) : 0;

    GDALRasterBandH band = ds.band(1);
    if (s.nodata)
      GDALSetRasterNoDataValue(band, *s.nodata);  // affects this handle's statistics only
    double mm[2] = {0, 0};
    CPLErrorReset();
    CPLErr err = GDALComputeRasterMinMax(band, TRUE, mm);
    if (err != CE_None || !std::isfinite(mm[0]) || !std::isfinite(mm[1])) {
      const std::string why = gdal_last_error();
      if (!why.empty() && why.find("no valid") == std::string::npos &&
          why.find("nodata") == std::string::npos)
        throw InputError(path + ": cannot read the raster data (" + why +
                         "); the file may be truncated or corrupt");
      CPLErrorReset();
      err = GDALComputeRasterMinMax(band, FALSE, mm);
      if (err != CE_None || !std::isfinite(mm[0]))
        throw InputError(path + ": holds no valid data (every sample is nodata" +
                         (src.nodata ? " = " + std::to_string(*src.nodata) : std::string()) + ")");
    }
    min_h = std::min(min_h, mm[0]);
    max_h = std::max(max_h, mm[1]);

    SpatialRef crs = SpatialRef::from_wkt(src.crs_wkt, path);
    if (!first_crs) first_crs = crs;
    src.x_shifts = {0.0};
    if (crs.is_geographic()) {
      const double x0 = src.geotransform[0], x1 = x0 + src.width * src.geotransform[1];
      const double lo = std::min(x0, x1), hi = std::max(x0, x1);
      if (hi > 180.0) src.x_shifts.push_back(-360.0);
      if (lo < -180.0) src.x_shifts.push_back(360.0);
    }
    plan.sources.push_back(std::move(src));
  }

  // 2. Height step on the global quantization grid.
  plan.step_m = s.precision ? *s.precision : (all_integer ? 1.0 : 0.01);
  const double max_abs = std::max(std::abs(min_h), std::abs(max_h));
  if (max_abs / plan.step_m >= tileformat::kMaxQuantum)
    throw InputError(plan.sources[0].path + ": heights up to " + std::to_string(max_abs) +
                     " m do not fit with --precision " + std::to_string(plan.step_m) +
                     "; use a larger --precision");
  plan.fill_q = static_cast<int32_t>(std::llround(min_h / plan.step_m));

  // 3. Tiling.
  std::optional<SpatialRef> target;
  if (s.tiling == "webmercator") {
    plan.tiling = Tiling::webmercator();
    target = SpatialRef::from_user_input("EPSG:3857", "internal");
  } else if (s.tiling == "geodetic") {
    plan.tiling = Tiling::geodetic();
    target = wgs84;
  } else {
    target = s.t_srs.empty() ? *first_crs : SpatialRef::from_user_input(s.t_srs, "--t_srs");
  }
  if (s.tiling != "local") plan.tiling.crs = target->wkt2();  // metadata records WKT2

  // 4. Data areas in the target CRS, and the source resolution there.
  Bounds ll_all{1e300, 1e300, -1e300, -1e300};
  double resolution = 1e300;
  std::vector<Bounds> local_areas;
  for (const auto& src : plan.sources) {
    const SpatialRef crs = SpatialRef::from_wkt(src.crs_wkt, src.path);
    const auto& gt = src.geotransform;
    const Bounds native{
        std::min(gt[0], gt[0] + src.width * gt[1]), std::min(gt[3], gt[3] + src.height * gt[5]),
        std::max(gt[0], gt[0] + src.width * gt[1]), std::max(gt[3], gt[3] + src.height * gt[5])};
    // Resolution: the source pixel at the data centre, measured in the target CRS.
    {
      CoordTransform to_target(crs, *target);
      const double cx = gt[0] + gt[1] * src.width / 2.0, cy = gt[3] + gt[5] * src.height / 2.0;
      std::vector<double> xs = {cx, cx + gt[1], cx}, ys = {cy, cy, cy + gt[5]};
      if (crs.is_geographic()) {
        for (auto& x : xs)
          x = std::remainder(x, 360.0);
        for (auto& y : ys)
          y = std::clamp(y, -kMercatorMaxLat + 1, kMercatorMaxLat - 1);
      }
      if (!to_target.transform(xs, ys))
        throw InputError(src.path + ": its centre cannot be transformed to the tiling CRS");
      const double dx = std::hypot(xs[1] - xs[0], ys[1] - ys[0]),
                   dy = std::hypot(xs[2] - xs[0], ys[2] - ys[0]);
      resolution = std::min(resolution, std::sqrt(dx * dy));
    }
    if (s.tiling == "local") {
      Bounds out;
      CoordTransform to_target(crs, *target);
      if (!to_target.transform_bounds(native, out))
        throw InputError(src.path + ": its extent cannot be transformed to " + target->name());
      local_areas.push_back(out);
      Bounds ll;
      CoordTransform to_ll(crs, wgs84);
      if (to_ll.transform_bounds(native, ll)) {
        ll_all = {std::min(ll_all.min_x, ll.min_x), std::min(ll_all.min_y, ll.min_y),
                  std::max(ll_all.max_x, ll.max_x), std::max(ll_all.max_y, ll.max_y)};
      }
      continue;
    }
    std::vector<Bounds> ll_parts;
    if (crs.is_geographic()) {
      for (double shift : src.x_shifts)
        ll_parts.push_back(
            {native.min_x + shift, native.min_y, native.max_x + shift, native.max_y});
    } else {
      Bounds ll;
      CoordTransform to_ll(crs, wgs84);
      if (!to_ll.transform_bounds(native, ll))
        throw InputError(src.path + ": its extent cannot be transformed to longitude/latitude");
      if (ll.min_x > ll.max_x) {  // crosses the antimeridian
        ll_parts.push_back({ll.min_x, ll.min_y, 180.0, ll.max_y});
        ll_parts.push_back({-180.0, ll.min_y, ll.max_x, ll.max_y});
      } else {
        ll_parts.push_back(ll);
      }
    }
    for (Bounds ll : ll_parts) {
      if (s.bbox) {
        const auto& b = *s.bbox;
        ll = {std::max(ll.min_x, b[0]), std::max(ll.min_y, b[1]), std::min(ll.max_x, b[2]),
              std::min(ll.max_y, b[3])};
      }
      auto area = lonlat_to_global(s.tiling, ll);
      if (!area) continue;
      plan.data_areas.push_back(*area);
      ll_all = {std::min(ll_all.min_x, std::max(ll.min_x, -180.0)),
                std::min(ll_all.min_y, std::max(ll.min_y, -90.0)),
                std::max(ll_all.max_x, std::min(ll.max_x, 180.0)),
                std::max(ll_all.max_y, std::min(ll.max_y, 90.0))};
    }
  }
  plan.source_resolution = resolution;
  if (!(resolution > 0) || !std::isfinite(resolution))
    throw InputError(plan.sources[0].path + ": cannot determine the pixel size in the tiling CRS");

  if (s.tiling == "local") {
    Bounds u = local_areas[0];
    for (const auto& a : local_areas)
      u = {std::min(u.min_x, a.min_x), std::min(u.min_y, a.min_y), std::max(u.max_x, a.max_x),
           std::max(u.max_y, a.max_y)};
    // Samples sit on source pixel centres when the tiling CRS is the source's:
    // the finest level then reproduces the source exactly.
    const double origin_x = u.min_x + resolution / 2, origin_y = u.max_y - resolution / 2;
    const double span = std::max(u.max_x - origin_x, origin_y - u.min_y);
    const int natural = std::max(
        0, static_cast<int>(std::ceil(std::log2(span / (plan.steps * resolution) - 1e-9))));
    plan.tiling = Tiling::local(target->wkt2(), origin_x, origin_y,
                                plan.steps * resolution * std::ldexp(1.0, natural));
    Bounds area = u;
    if (s.bbox) {
      Bounds bb_ll{(*s.bbox)[0], (*s.bbox)[1], (*s.bbox)[2], (*s.bbox)[3]}, bb;
      CoordTransform ll_to_target(wgs84, *target);
      if (!ll_to_target.transform_bounds(bb_ll, bb))
        throw UsageError("--bbox cannot be transformed to " + target->name());
      area = {std::max(u.min_x, bb.min_x), std::max(u.min_y, bb.min_y), std::min(u.max_x, bb.max_x),
              std::min(u.max_y, bb.max_y)};
    }
    if (area.min_x < area.max_x && area.min_y < area.max_y) plan.data_areas.push_back(area);
  }
  plan.lonlat = ll_all;
  if (plan.data_areas.empty()) {
    if (s.bbox)
      throw InputError("--bbox does not intersect the data of " + plan.sources[0].path +
                       (s.inputs.size() > 1 ? " (and the other inputs)" : "") +
                       "; check the bbox (west,south,east,north in degrees)");
    throw InputError(plan.sources[0].path + ": the data lies outside the " + s.tiling +
                     " tiling's extent");
  }

  // 5. Zoom range: the finest zoom is the first whose sample spacing reaches
  // the source resolution.
  int natural_max = 0;
  while (natural_max < 24 &&
         plan.tiling.sample_spacing(natural_max, plan.steps) > resolution * (1 + 1e-9))
    ++natural_max;
  plan.max_zoom = s.max_zoom.value_or(natural_max);
  plan.min_zoom = s.min_zoom.value_or(0);
  if (plan.max_zoom > natural_max + 6)
    throw UsageError("--max-zoom " + std::to_string(plan.max_zoom) +
                     " is out of range: the data's finest zoom is " + std::to_string(natural_max) +
                     " (at most 6 zooms deeper are allowed)");
  if (plan.min_zoom > plan.max_zoom)
    throw UsageError("--min-zoom " + std::to_string(plan.min_zoom) +
                     " is larger than the maximum zoom " + std::to_string(plan.max_zoom));
  return plan;
}

}  // namespace globe
