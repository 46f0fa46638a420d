// The flat base under layers without terrain (see flat_base.hpp).
#include "app/flat_base.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "camera/proj_crs.hpp"
#include "runtime/area_package.hpp"
#include "runtime/errors.hpp"
#include "runtime/image_package.hpp"
#include "runtime/line_package.hpp"
#include "runtime/point_package.hpp"
#include "tileformat/kpatch.hpp"
#include "tileformat/mblock.hpp"
#include "tileformat/metadata.hpp"
#include "tileformat/package.hpp"

namespace globe::viewer {

namespace {

using tileformat::Bounds;
using tileformat::Scheme;
using tileformat::Tiling;

constexpr int kBlockSize = 257, kLattice = 16;  // the tiler's defaults
constexpr int kWholeEarthZooms = 2;             // zooms 0..2 cover the tiling's whole extent
constexpr double kMaxChordM = 7100;             // a chord of 7.1 km sags 1 m below the ellipsoid
constexpr uint64_t kMaxTilesPerZoom = 16384;
constexpr double kMetresPerDegree = 111320;

struct Layer {
  std::string path;
  Tiling tiling;
  Bounds lonlat;
  bool has_bounds = false;
};

Layer first_layer(const PackageSet& set) {
  if (set.lines) {
    const LinePackage p = open_line_package(*set.lines);
    return {*set.lines, p.tiling, p.meta.common.lonlat, p.meta.common.has_bounds};
  }
  if (set.points) {
    const PointPackage p = open_point_package(*set.points);
    return {*set.points, p.meta.common.tiling, p.meta.common.lonlat, p.meta.common.has_bounds};
  }
  if (set.areas) {
    const AreaPackage p = open_area_package(*set.areas);
    return {*set.areas, p.meta.common.tiling, p.meta.common.lonlat, p.meta.common.has_bounds};
  }
  if (!set.images.empty()) {
    const ImagePackage p = open_image_package(set.images.front());
    return {set.images.front(), p.tiling, p.meta.common.lonlat, p.meta.common.has_bounds};
  }
  throw InputError(
      "no package to draw: give a terrain, or lines, points, areas or imagery to draw "
      "over a flat base");
}

// The layer's bounds in its tiling's CRS (densified edges), cut to the
// tiling's extent.
Bounds crs_bounds(const Layer& l) {
  const Bounds extent = l.tiling.extent();
  if (!l.has_bounds) return extent;
  ProjTransform to_crs("EPSG:4326", l.tiling.crs, l.path);
  const double lat_limit = l.tiling.scheme == Scheme::kWebMercator ? 85.05 : 90;
  Bounds b{1e300, 1e300, -1e300, -1e300};
  constexpr int kSteps = 16;
  for (int j = 0; j <= kSteps; ++j)
    for (int i = 0; i <= kSteps; ++i) {
      if (i != 0 && i != kSteps && j != 0 && j != kSteps) continue;  // the edges
      double x = l.lonlat.min_x + (l.lonlat.max_x - l.lonlat.min_x) * i / kSteps;
      double y = std::clamp(l.lonlat.min_y + (l.lonlat.max_y - l.lonlat.min_y) * j / kSteps,
                            -lat_limit, lat_limit);
      if (!to_crs.transform(x, y)) continue;
      b.min_x = std::min(b.min_x, x), b.max_x = std::max(b.max_x, x);
      b.min_y = std::min(b.min_y, y), b.max_y = std::max(b.max_y, y);
    }
  if (!(b.min_x <= b.max_x)) return extent;
  return {std::max(b.min_x, extent.min_x), std::max(b.min_y, extent.min_y),
          std::min(b.max_x, extent.max_x), std::min(b.max_y, extent.max_y)};
}

// The deepest zoom the base needs: chords of the globe's mesh sag < 1 m
// (a local tiling is drawn on the flat frame only, where any zoom is exact).
int deepest_zoom(const Tiling& t) {
  if (t.scheme == Scheme::kLocal) return kWholeEarthZooms;
  const double per_unit = t.scheme == Scheme::kGeodetic ? kMetresPerDegree : 1.0;
  int z = 0;
  while (t.tile_size(z) * per_unit / (kBlockSize - 1) > kMaxChordM)
    ++z;
  return std::max(z, kWholeEarthZooms);
}

}  // namespace

FlatBase::FlatBase(const PackageSet& set) {
  const Layer layer = first_layer(set);
  path_ = (std::filesystem::temp_directory_path() /
           ("globe-view-base-" + std::to_string(::getpid()) + ".mbtiles"))
              .string();
  tileformat::MBlock block;
  block.size = kBlockSize;
  block.lattice = kLattice;
  block.step = 1.0;
  block.q.assign(size_t(kBlockSize) * kBlockSize, 0);
  block.vertex_error.assign(
      tileformat::kpatch_vertex_count(tileformat::kpatch_depth(kBlockSize - 1, kLattice)), 0);
  const std::vector<uint8_t> blob = tileformat::encode_mblock(block);

  const Bounds area = crs_bounds(layer);
  const int deepest = deepest_zoom(layer.tiling);
  int max_zoom = 0;
  try {
    tileformat::PackageWriter w(path_, tileformat::IfExists::kOverwrite);
    for (int z = 0; z <= deepest; ++z) {
      const tileformat::TileRange r =
          layer.tiling.tiles_covering(z <= kWholeEarthZooms ? layer.tiling.extent() : area, z);
      if (r.empty() || r.count() > kMaxTilesPerZoom) break;
      for (uint32_t y = r.min_y; y <= r.max_y; ++y)
        for (uint32_t x = r.min_x; x <= r.max_x; ++x)
          w.put_tile({z, x, y}, blob);
      max_zoom = z;
    }
    tileformat::TerrainMetadata m;
    m.common.name = "flat base";
    m.common.format = tileformat::kMBlockFormat;
    m.common.type = "baselayer";
    m.common.description = "zero heights under " + layer.path + " (globe-view without terrain)";
    m.common.lonlat = layer.has_bounds ? layer.lonlat : layer.tiling.lonlat_limits();
    m.common.min_zoom = 0;
    m.common.max_zoom = max_zoom;
    m.common.tiling = layer.tiling;
    m.common.generator = "globe-view";
    m.resampling = "none";
    m.block_size = kBlockSize;
    m.lattice = kLattice;
    m.height_step = 1.0;
    w.set_metadata(tileformat::to_metadata(m));
    w.commit();
  } catch (const std::exception& e) {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
    throw OutputError("cannot write the flat base under " + layer.path + " to " + path_ + ": " +
                      e.what());
  }
}

FlatBase::~FlatBase() {
  std::error_code ec;
  std::filesystem::remove(path_, ec);
}

}  // namespace globe::viewer
