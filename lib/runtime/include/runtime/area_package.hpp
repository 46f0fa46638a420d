// Opening an existing area package for inspection, export and serving: the
// reader plus the metadata, checked once.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "runtime/line_style.hpp"
#include "tileformat/metadata.hpp"
#include "tileformat/package.hpp"

namespace globe {

struct AreaPackage {
  std::unique_ptr<tileformat::PackageReader> reader;
  tileformat::AreaMetadata meta;        // every key, as lib/tileformat reads it
  std::vector<NamedLineStyle> classes;  // style classes by class id (metadata globe:classes)
};

// Throws InputError naming the file if it is missing, not a package, or not
// an area package.
AreaPackage open_area_package(const std::string& path);

}  // namespace globe
