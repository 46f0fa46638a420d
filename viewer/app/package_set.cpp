// Sorting the viewer's packages (see package_set.hpp).
#include "app/package_set.hpp"

#include <cmath>

#include "camera/proj_crs.hpp"
#include "runtime/errors.hpp"
#include "runtime/image_package.hpp"
#include "runtime/package_open.hpp"
#include "tileformat/line_tile.hpp"
#include "tileformat/package.hpp"

namespace globe::viewer {

PackageSet sort_packages(const std::vector<std::string>& paths) {
  PackageSet set;
  for (const std::string& path : paths) {
    const std::string format = package_format(*open_source(path), path);
    const auto kind = tileformat::package_kind_of_format(format);
    if (kind == tileformat::PackageKind::kTerrain) {
      if (!set.terrain.empty())
        throw UsageError("two terrain packages (" + set.terrain + ", " + path +
                         "); globe-view draws one terrain per view");
      set.terrain = path;
    } else if (kind == tileformat::PackageKind::kLines) {
      if (set.lines)
        throw UsageError("two line packages (" + *set.lines + ", " + path +
                         "); globe-view draws one line package per view");
      set.lines = path;
    } else if (kind == tileformat::PackageKind::kImage) {
      set.images.push_back(path);
    } else if (kind == tileformat::PackageKind::kPoints) {
      if (set.points)
        throw UsageError("two point packages (" + *set.points + ", " + path +
                         "); globe-view draws the charts of one point package per view");
      set.points = path;
    } else if (kind == tileformat::PackageKind::kAreas) {
      if (set.areas)
        throw UsageError("two area packages (" + *set.areas + ", " + path +
                         "); globe-view draws one area package per view");
      set.areas = path;
    } else if (kind == tileformat::PackageKind::kAnalysis) {
      if (set.analysis)
        throw UsageError("two analysis packages (" + *set.analysis + ", " + path +
                         "); globe-view draws one analysis package per view");
      set.analysis = path;
    } else {
      throw InputError(path + ": format '" + format +
                       "' is not a package globe-view draws (terrain, image, line, analysis, "
                       "point, area)");
    }
  }
  if (set.terrain.empty() && set.analysis)
    throw UsageError(*set.analysis +
                     " is an analysis of a terrain; give that terrain package too (globe-view "
                     "TERRAIN ANALYSIS)");
  return set;
}

namespace {

bool same_tiling(const tileformat::Tiling& t, const std::string& terrain_path,
                 const tileformat::Tiling& o, const std::string& other_path) {
  auto close = [](double a, double b) {
    return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(a) + std::abs(b));
  };
  bool same = t.scheme == o.scheme && close(t.origin_x, o.origin_x) &&
              close(t.origin_y, o.origin_y) && close(t.root_size, o.root_size) &&
              t.roots_x == o.roots_x && t.roots_y == o.roots_y;
  if (same && t.scheme == tileformat::Scheme::kLocal && t.crs != o.crs)
    same = crs_equivalent(t.crs, terrain_path, o.crs, other_path);
  return same;
}

[[noreturn]] void throw_tiling_differs(const tileformat::Tiling& t, const std::string& terrain_path,
                                       const tileformat::Tiling& o, const std::string& other_path,
                                       const std::string& what_crosses) {
  throw InputError(other_path + ": its tiling (" + std::string(tileformat::scheme_name(o.scheme)) +
                   ", root " + std::to_string(o.root_size) + ") differs from the terrain's (" +
                   terrain_path + ": " + tileformat::scheme_name(t.scheme) + ", root " +
                   std::to_string(t.root_size) + "); " + what_crosses +
                   "rebuild it with the terrain's --tiling (and --like for local tilings)");
}

}  // namespace

void check_same_tiling(const tileformat::Tiling& t, const std::string& terrain_path,
                       const tileformat::Tiling& o, const std::string& other_path) {
  if (!same_tiling(t, terrain_path, o, other_path))
    throw_tiling_differs(t, terrain_path, o, other_path, "");
}

CrsCross layer_cross(const tileformat::Tiling& terrain, const std::string& terrain_path,
                     const tileformat::Tiling& other, const std::string& other_path) {
  const CrsCross cross = crs_cross(terrain, other);
  if (cross == CrsCross::kGeodeticToMercator || cross == CrsCross::kMercatorToGeodetic)
    return cross;
  if (!same_tiling(terrain, terrain_path, other, other_path))
    throw_tiling_differs(terrain, terrain_path, other, other_path,
                         "lines and points cross between geodetic and webmercator only: ");
  return CrsCross::kSame;
}

}  // namespace globe::viewer
