// Opening an existing point package (docs/tileformat.md §11) for inspection
// or drawing: the reader plus its metadata, checked once.
#pragma once

#include <memory>
#include <string>

#include "tileformat/metadata.hpp"
#include "tileformat/package.hpp"

namespace globe {

struct PointPackage {
  std::unique_ptr<tileformat::PackageReader> reader;
  tileformat::PointMetadata meta;  // every key, as lib/tileformat reads it
};

// Throws InputError naming the file if it is missing, not a package, or not
// a point package.
PointPackage open_point_package(const std::string& path);

}  // namespace globe
