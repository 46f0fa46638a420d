// Opening terrain packages (see terrain_package.hpp).
#include "terrain_package.hpp"

#include "errors.hpp"
#include "tileformat/error.hpp"

namespace globe {

TerrainPackage open_terrain_package(const std::string& path) {
  TerrainPackage p;
  try {
    p.reader = std::make_unique<tileformat::PackageReader>(path);
  } catch (const tileformat::PackageError& e) {
    throw InputError(e.what());
  }
  const auto fmt = p.reader->meta("format");
  if (!fmt) throw InputError(path + ": metadata has no 'format'; not a globe package");
  if (*fmt != tileformat::kMBlockFormat)
    throw InputError(path + ": a '" + *fmt + "' package, not a terrain package (" +
                     tileformat::kMBlockFormat + ")");
  auto num = [&](const char* key) {
    auto v = p.reader->meta(key);
    if (!v) throw InputError(path + ": metadata key " + key + " is missing (tileformat §3.2)");
    try {
      return std::stod(*v);
    } catch (const std::exception&) {
      throw InputError(path + ": metadata key " + key + " is not a number (tileformat §3.2)");
    }
  };
  try {
    p.tiling = tileformat::Tiling::from_metadata(p.reader->metadata());
  } catch (const tileformat::FormatError& e) {
    throw InputError(path + ": " + e.what());
  }
  p.block_size = static_cast<int>(num("globe:block_size"));
  p.lattice = static_cast<int>(num("globe:kpatch_lattice"));
  p.step_m = num("globe:height_step");
  p.min_zoom = static_cast<int>(num("minzoom"));
  p.max_zoom = static_cast<int>(num("maxzoom"));
  return p;
}

}  // namespace globe
