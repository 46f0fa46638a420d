// Raster inputs in a tiling (see raster_footprint.hpp, docs/terrain.md "Planning").
#include "raster/raster_footprint.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "runtime/errors.hpp"
#include "tileformat/error.hpp"
#include "tileformat/package.hpp"

namespace globe {
namespace {

using tileformat::Bounds;
using tileformat::Scheme;
using tileformat::Tiling;

constexpr double kMercatorMaxLat = 85.05112877980659;
constexpr double kEarthRadius = 6378137.0;
constexpr double kPi = 3.14159265358979323846;

double mercator_y(double lat_deg) {
  const double lat = std::clamp(lat_deg, -kMercatorMaxLat, kMercatorMaxLat) * kPi / 180.0;
  return kEarthRadius * std::log(std::tan(kPi / 4 + lat / 2));
}
double mercator_x(double lon_deg) {
  return kEarthRadius * lon_deg * kPi / 180.0;
}

// Lon/lat rectangle -> tiling CRS for the global schemes; empty if outside.
std::optional<Bounds> lonlat_to_global(Scheme scheme, Bounds ll) {
  ll.min_x = std::max(ll.min_x, -180.0);
  ll.max_x = std::min(ll.max_x, 180.0);
  const double lat_limit = scheme == Scheme::kWebMercator ? kMercatorMaxLat : 90.0;
  ll.min_y = std::max(ll.min_y, -lat_limit);
  ll.max_y = std::min(ll.max_y, lat_limit);
  if (!(ll.min_x < ll.max_x && ll.min_y < ll.max_y)) return std::nullopt;
  if (scheme == Scheme::kGeodetic) return ll;
  return Bounds{mercator_x(ll.min_x), mercator_y(ll.min_y), mercator_x(ll.max_x),
                mercator_y(ll.max_y)};
}

Bounds unite(const Bounds& a, const Bounds& b) {
  return {std::min(a.min_x, b.min_x), std::min(a.min_y, b.min_y), std::max(a.max_x, b.max_x),
          std::max(a.max_y, b.max_y)};
}

Tiling tiling_of_package(const std::string& like) {
  try {
    tileformat::PackageReader reader(like);
    return Tiling::from_metadata(reader.metadata());
  } catch (const tileformat::FormatError& e) {
    throw InputError(like + " (--like): " + e.what());
  } catch (const tileformat::PackageError& e) {
    throw InputError(like + " (--like): " + e.what() + "; pass a package built by globe-tiler");
  }
}

// The finest source pixel in tiling units: at 9 x 9 points over the source,
// the local mapping J (tiling units per source pixel) is measured and the
// pixel's size taken along its worst axis (1 / the largest entry of J^-1:
// the most source pixels one tiling unit crosses in either source axis).
// The minimum over the points makes the finest zoom upsample everywhere, so
// warping never widens its kernel (what a measure at the data centre missed
// for data around a pole or far from the equator in webmercator).
double source_resolution(const RasterSource& src, const SpatialRef& crs, const SpatialRef& target) {
  const auto& gt = src.geotransform;
  CoordTransform to_target(crs, target);
  const bool geographic_target = target.is_geographic();
  constexpr int kPoints = 9;
  std::vector<double> xs, ys;
  for (int j = 0; j < kPoints; ++j)
    for (int i = 0; i < kPoints; ++i) {
      const double c = (i + 0.5) * src.width / kPoints, r = (j + 0.5) * src.height / kPoints;
      for (auto [dc, dr] : {std::pair{0.0, 0.0}, std::pair{1.0, 0.0}, std::pair{0.0, 1.0}}) {
        double x = gt[0] + (c + dc) * gt[1], y = gt[3] + (r + dr) * gt[5];
        if (crs.is_geographic()) {
          x = std::remainder(x, 360.0);  // into -180..180, the antimeridian side kept per point
          y = std::clamp(y, -89.999, 89.999);
        }
        xs.push_back(x);
        ys.push_back(y);
      }
    }
  std::vector<int> ok;
  to_target.transform(xs, ys, ok);
  double finest = HUGE_VAL;
  for (size_t p = 0; p + 2 < xs.size(); p += 3) {
    if (!ok[p] || !ok[p + 1] || !ok[p + 2]) continue;
    auto diff = [&](size_t a, double& dx, double& dy) {
      dx = xs[a] - xs[p];
      dy = ys[a] - ys[p];
      if (geographic_target) dx = std::remainder(dx, 360.0);
    };
    double j00, j10, j01, j11;  // J columns: per source column, per source row
    diff(p + 1, j00, j10);
    diff(p + 2, j01, j11);
    const double det = j00 * j11 - j01 * j10;
    if (!(std::abs(det) > 0) || !std::isfinite(det)) continue;
    // J^-1 = [j11 -j01; -j10 j00] / det
    const double worst =
        std::max({std::abs(j11), std::abs(j01), std::abs(j10), std::abs(j00)}) / std::abs(det);
    finest = std::min(finest, 1 / worst);
  }
  if (!std::isfinite(finest))
    throw InputError(src.path + ": its pixels cannot be transformed to the tiling CRS");
  return finest;
}

// `wrapped` with the source's resolved CRS, geotransform `gt` and nodata.
GdalDataset with_georeferencing(GdalDataset wrapped, const RasterSource& src,
                                const std::array<double, 6>& gt, std::optional<double> nodata,
                                const std::vector<int>& nodata_bands) {
  wrapped.set_geotransform(gt);
  wrapped.set_crs(SpatialRef::from_wkt(src.crs_wkt, src.path));
  if (nodata)
    for (int b : nodata_bands)
      wrapped.set_nodata(b, *nodata);
  return wrapped;
}

}  // namespace

int periodic_columns(const RasterSource& src) {
  if (src.has_mask_band || !(src.geotransform[1] > 0) ||
      !SpatialRef::from_wkt(src.crs_wkt, src.path).is_geographic())
    return 0;
  const double distinct = 360.0 / src.geotransform[1];
  const int n = int(std::lround(distinct));
  if (std::abs(distinct - n) > 1e-6 || n < 2 * kWrapColumns) return 0;
  return src.width == n || src.width == n + 1 ? n : 0;
}

GdalDataset georeferenced_copy(GDALDatasetH in, const RasterSource& src, double shift,
                               std::optional<double> nodata, const std::vector<int>& nodata_bands) {
  auto gt = src.geotransform;
  gt[0] += shift;
  // A grid once around the Earth (its last column perhaps repeating the
  // first) is extended periodically, its columns rotated to start
  // kWrapColumns west of -180 and running as far past +180, every longitude
  // lies between two of its pixel centres, well inside (docs/terrain.md
  // "Longitude wrap").
  if (const int n = periodic_columns(src); n > 0 && shift == 0) {
    const double step = gt[1], west = -180.0 - kWrapColumns * step;
    const int64_t c = int64_t(std::ceil((west - gt[0]) / step - 1e-9));
    const int first = int(((c % n) + n) % n);
    gt[0] += double(c) * step;
    GdalDataset wrapped =
        GdalDataset::periodic_columns_vrt(in, first, n, n + 2 * kWrapColumns, src.path);
    return with_georeferencing(std::move(wrapped), src, gt, nodata, nodata_bands);
  }
  return with_georeferencing(GdalDataset::vrt_copy(in, src.path), src, gt, nodata, nodata_bands);
}

std::vector<double> warp_shifts(const RasterSource& src) {
  const double span = std::abs(src.width * src.geotransform[1]);
  if (src.x_shifts.size() <= 1 || span <= 360.0 || periodic_columns(src) > 0) return {0.0};
  std::vector<double> shifts;
  for (double s : src.x_shifts)
    if (s != 0) shifts.push_back(s);
  shifts.push_back(0.0);
  return shifts;
}

void check_tiling_options(const BuildOptions& s, const std::string& like) {
  if (!s.t_srs.empty() && s.tiling != Scheme::kLocal)
    throw UsageError(std::string("--t_srs applies to --tiling local only (") +
                     scheme_name(s.tiling) + " has a fixed CRS)");
  if (!like.empty() && (s.tiling != Scheme::kWebMercator || !s.t_srs.empty()))
    throw UsageError("--like takes the tiling from the package; drop --tiling/--t_srs");
}

RasterSource describe_raster(const GdalDataset& ds, const std::string& path,
                             const std::optional<SpatialRef>& s_srs) {
  RasterSource src;
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
  src.has_mask_band = GdalDataset::has_mask_band(ds.get());
  src.crs_wkt = s_srs ? s_srs->wkt2() : ds.crs_wkt();
  if (src.crs_wkt.empty()) throw InputError(path + ": no CRS found; pass --s_srs EPSG:xxxx");
  std::error_code ec;
  src.file_bytes =
      std::filesystem::is_regular_file(path, ec) ? std::filesystem::file_size(path, ec) : 0;
  return src;
}

Footprint plan_footprint(std::vector<RasterSource>& sources, const BuildOptions& s,
                         const std::string& like, TileGrid grid) {
  check_tiling_options(s, like);
  Footprint f;
  const SpatialRef wgs84 = SpatialRef::from_user_input("EPSG:4326", "internal");
  std::optional<SpatialRef> target;
  Scheme scheme = s.tiling;
  bool tiling_fixed = true;
  if (!like.empty()) {
    f.tiling = tiling_of_package(like);
    scheme = f.tiling.scheme;
    target = SpatialRef::from_wkt(f.tiling.crs, like);
  } else if (s.tiling == Scheme::kWebMercator) {
    f.tiling = Tiling::webmercator();
    target = SpatialRef::from_user_input("EPSG:3857", "internal");
  } else if (s.tiling == Scheme::kGeodetic) {
    f.tiling = Tiling::geodetic();
    target = wgs84;
  } else {
    tiling_fixed = false;
    target = s.t_srs.empty() ? SpatialRef::from_wkt(sources[0].crs_wkt, sources[0].path)
                             : SpatialRef::from_user_input(s.t_srs, "--t_srs");
  }
  if (like.empty() && s.tiling != Scheme::kLocal)
    f.tiling.crs = target->wkt2();  // metadata records WKT2

  Bounds ll_all{1e300, 1e300, -1e300, -1e300};
  const double lat_limit = scheme == Scheme::kWebMercator ? kMercatorMaxLat : 90.0;
  double north = -90, south = 90;  // pixel centres of the global schemes' data
  double resolution = 1e300;
  std::vector<Bounds> local_areas;
  for (auto& src : sources) {
    const SpatialRef crs = SpatialRef::from_wkt(src.crs_wkt, src.path);
    const auto& gt = src.geotransform;
    src.x_shifts = {0.0};
    if (crs.is_geographic()) {
      const double x0 = gt[0], x1 = x0 + src.width * gt[1];
      if (std::max(x0, x1) > 180.0) src.x_shifts.push_back(-360.0);
      if (std::min(x0, x1) < -180.0) src.x_shifts.push_back(360.0);
    }
    const Bounds native{
        std::min(gt[0], gt[0] + src.width * gt[1]), std::min(gt[3], gt[3] + src.height * gt[5]),
        std::max(gt[0], gt[0] + src.width * gt[1]), std::max(gt[3], gt[3] + src.height * gt[5])};
    resolution = std::min(resolution, source_resolution(src, crs, *target));
    if (scheme == Scheme::kLocal) {
      Bounds out;
      CoordTransform to_target(crs, *target);
      if (!to_target.transform_bounds(native, out))
        throw InputError(src.path + ": its extent cannot be transformed to " + target->name());
      local_areas.push_back(out);
      Bounds ll;
      CoordTransform to_ll(crs, wgs84);
      if (to_ll.transform_bounds(native, ll)) ll_all = unite(ll_all, ll);
      continue;
    }
    std::vector<Bounds> ll_parts;
    // Latitudes of the northern- and southernmost pixel centres (pixel
    // areas reaching past a limit by half a pixel lose no sample).
    const double half_y = crs.is_geographic() ? std::abs(gt[5]) / 2 : 0.0;
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
      if (ll.min_x < ll.max_x && ll.min_y < ll.max_y) {
        north = std::max(north, std::min(ll.max_y - half_y, 90.0));
        south = std::min(south, std::max(ll.min_y + half_y, -90.0));
      }
      auto area = lonlat_to_global(scheme, ll);
      if (!area) continue;
      f.data_areas.push_back(*area);
      ll_all = unite(ll_all, {std::max(ll.min_x, -180.0), std::max(ll.min_y, -lat_limit),
                              std::min(ll.max_x, 180.0), std::min(ll.max_y, lat_limit)});
    }
  }
  if (scheme != Scheme::kLocal) {
    std::string out;
    char buf[160];
    if (north > lat_limit + 1e-9) {
      std::snprintf(buf, sizeof buf, "latitudes %.7g..%.7g", lat_limit, north);
      out = buf;
    }
    if (south < -lat_limit - 1e-9) {
      std::snprintf(buf, sizeof buf, "%.7g..%.7g", south, -lat_limit);
      out += (out.empty() ? "latitudes " : " and ") + std::string(buf);
    }
    if (!out.empty()) f.left_out = out + " (outside the " + scheme_name(scheme) + " tiling)";
  }
  f.source_resolution = resolution;
  if (!(resolution > 0) || !std::isfinite(resolution))
    throw InputError(sources[0].path + ": cannot determine the pixel size in the tiling CRS");

  if (scheme == Scheme::kLocal) {
    Bounds u = local_areas[0];
    for (const auto& a : local_areas)
      u = unite(u, a);
    if (!tiling_fixed) {
      // Terrain: samples sit on source pixel centres when the tiling CRS is
      // the source's, so the finest level reproduces the source exactly.
      // Imagery: tile pixels coincide with source pixels.
      const double inset = grid.centres_on_corners ? resolution / 2 : 0.0;
      const double origin_x = u.min_x + inset, origin_y = u.max_y - inset;
      const double span = std::max(u.max_x - origin_x, origin_y - u.min_y);
      const int natural = std::max(
          0, static_cast<int>(std::ceil(std::log2(span / (grid.pixels * resolution) - 1e-9))));
      f.tiling = Tiling::local(target->wkt2(), origin_x, origin_y,
                               grid.pixels * resolution * std::ldexp(1.0, natural));
    }
    Bounds area = u;
    if (s.bbox) {
      Bounds bb_ll{(*s.bbox)[0], (*s.bbox)[1], (*s.bbox)[2], (*s.bbox)[3]}, bb;
      CoordTransform ll_to_target(wgs84, *target);
      if (!ll_to_target.transform_bounds(bb_ll, bb))
        throw UsageError("--bbox cannot be transformed to " + target->name());
      area = {std::max(u.min_x, bb.min_x), std::max(u.min_y, bb.min_y), std::min(u.max_x, bb.max_x),
              std::min(u.max_y, bb.max_y)};
    }
    if (tiling_fixed) {  // an adopted local tiling may not cover all the data
      const Bounds ext = f.tiling.extent();
      area = {std::max(area.min_x, ext.min_x), std::max(area.min_y, ext.min_y),
              std::min(area.max_x, ext.max_x), std::min(area.max_y, ext.max_y)};
    }
    if (area.min_x < area.max_x && area.min_y < area.max_y) f.data_areas.push_back(area);
  }
  f.lonlat = ll_all;
  if (f.data_areas.empty()) {
    if (s.bbox)
      throw InputError("--bbox does not intersect the data of " + sources[0].path +
                       (sources.size() > 1 ? " (and the other inputs)" : "") +
                       "; check the bbox (west,south,east,north in degrees)");
    throw InputError(
        sources[0].path + ": the data lies outside the " +
        (like.empty() ? std::string(scheme_name(s.tiling)) + " tiling's" : like + " package's") +
        " extent");
  }
  while (f.natural_max_zoom < 24 &&
         f.tiling.sample_spacing(f.natural_max_zoom, grid.pixels) > resolution * (1 + 1e-9))
    ++f.natural_max_zoom;
  f.max_zoom = s.max_zoom.value_or(f.natural_max_zoom);
  f.min_zoom = s.min_zoom.value_or(0);
  if (f.max_zoom > f.natural_max_zoom + 6)
    throw UsageError("--max-zoom " + std::to_string(f.max_zoom) +
                     " is out of range: the data's finest zoom is " +
                     std::to_string(f.natural_max_zoom) + " (at most 6 zooms deeper are allowed)");
  if (f.min_zoom > f.max_zoom)
    throw UsageError("--min-zoom " + std::to_string(f.min_zoom) +
                     " is larger than the maximum zoom " + std::to_string(f.max_zoom));
  return f;
}

}  // namespace globe
