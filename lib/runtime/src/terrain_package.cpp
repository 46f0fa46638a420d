// Opening terrain packages (see terrain_package.hpp).
#include "runtime/terrain_package.hpp"

#include "runtime/package_open.hpp"

namespace globe {

TerrainPackage open_terrain_package(const std::string& path) {
  TerrainPackage p;
  p.reader = open_package_of_kind(path, tileformat::PackageKind::kTerrain);
  p.meta =
      read_metadata(path, [&] { return tileformat::read_terrain_metadata(p.reader->metadata()); });
  p.tiling = p.meta.common.tiling;
  p.block_size = p.meta.block_size;
  p.lattice = p.meta.lattice;
  p.step_m = p.meta.height_step;
  p.min_zoom = p.meta.common.min_zoom;
  p.max_zoom = p.meta.common.max_zoom;
  return p;
}

}  // namespace globe
