// Opening an existing line-cluster package for inspection: the reader plus
// the metadata every inspection command needs, checked once.
#pragma once

#include "tileformat/metadata.hpp"

#include <memory>
#include <string>
#include <vector>

#include "runtime/line_style.hpp"
#include "runtime/package_open.hpp"
#include "tileformat/package.hpp"
#include "tileformat/tiling.hpp"

namespace globe {

struct LinePackage {
  // The package file or, in globe-view, a remote source (package_open.hpp).
  std::unique_ptr<tileformat::TileReader> reader;
  // The file itself, for its other tables and whole-package reads; throws
  // InputError for a remote source.
  tileformat::PackageReader& file() const { return package_file(*reader); }
  tileformat::LineMetadata meta;  // every key, as lib/tileformat reads it
  tileformat::Tiling tiling;      // the fields below repeat meta for brevity
  int extent = 0, cluster_grid = 0, min_zoom = 0, max_zoom = 0;
  std::vector<NamedLineStyle> classes;  // by class id (metadata globe:classes)
};

// Throws InputError naming the file if it is missing, not a package, or not
// a line-cluster package.
LinePackage open_line_package(const std::string& path);

}  // namespace globe
