// Opening an existing terrain package for inspection: the reader plus the
// metadata every inspection command needs, checked once.
#pragma once

#include "tileformat/metadata.hpp"

#include <memory>
#include <string>

#include "runtime/package_open.hpp"
#include "tileformat/package.hpp"
#include "tileformat/tiling.hpp"

namespace globe {

struct TerrainPackage {
  // The package file or, in globe-view, a remote source (package_open.hpp).
  std::unique_ptr<tileformat::TileReader> reader;
  // The file itself, for its other tables and whole-package reads; throws
  // InputError for a remote source.
  tileformat::PackageReader& file() const { return package_file(*reader); }
  tileformat::TerrainMetadata meta;  // every key, as lib/tileformat reads it
  tileformat::Tiling tiling;         // the fields below repeat meta for brevity
  int block_size = 0, lattice = 0, min_zoom = 0, max_zoom = 0;
  double step_m = 0;
};

// Throws InputError naming the file if it is missing, not a package, or not
// a terrain package.
TerrainPackage open_terrain_package(const std::string& path);

}  // namespace globe
