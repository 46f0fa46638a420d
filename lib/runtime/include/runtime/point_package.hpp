// Opening an existing point package (docs/tileformat.md §11) for inspection
// or drawing: the reader plus its metadata, checked once.
#pragma once

#include <memory>
#include <string>

#include "runtime/package_open.hpp"
#include "tileformat/metadata.hpp"
#include "tileformat/package.hpp"

namespace globe {

struct PointPackage {
  // The package file or, in globe-view, a remote source (package_open.hpp).
  std::unique_ptr<tileformat::TileReader> reader;
  // The file itself, for its other tables and whole-package reads; throws
  // InputError for a remote source.
  tileformat::PackageReader& file() const { return package_file(*reader); }
  tileformat::PointMetadata meta;  // every key, as lib/tileformat reads it
};

// Throws InputError naming the file if it is missing, not a package, or not
// a point package.
PointPackage open_point_package(const std::string& path);

}  // namespace globe
