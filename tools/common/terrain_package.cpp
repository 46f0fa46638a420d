// Opening terrain packages (see terrain_package.hpp).
#include "terrain_package.hpp"

#include "package_open.hpp"

namespace globe {

TerrainPackage open_terrain_package(const std::string& path) {
  TerrainPackage p;
  p.reader = open_package_of_format(path, tileformat::kMBlockFormat, "terrain");
  p.tiling = meta_tiling(*p.reader, path);
  p.block_size = static_cast<int>(meta_number(*p.reader, path, "globe:block_size"));
  p.lattice = static_cast<int>(meta_number(*p.reader, path, "globe:kpatch_lattice"));
  p.step_m = meta_number(*p.reader, path, "globe:height_step");
  p.min_zoom = static_cast<int>(meta_number(*p.reader, path, "minzoom"));
  p.max_zoom = static_cast<int>(meta_number(*p.reader, path, "maxzoom"));
  return p;
}

}  // namespace globe
