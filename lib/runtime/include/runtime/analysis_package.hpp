// Opening an existing analysis package (tileformat §9) for inspection and
// drawing: the reader plus its metadata, checked once.
#pragma once

#include <memory>
#include <string>

#include "runtime/package_open.hpp"
#include "tileformat/metadata.hpp"
#include "tileformat/package.hpp"

namespace globe {

struct AnalysisPackage {
  // The package file or, in globe-view, a remote source (package_open.hpp).
  std::unique_ptr<tileformat::TileReader> reader;
  // The file itself, for its other tables and whole-package reads; throws
  // InputError for a remote source.
  tileformat::PackageReader& file() const { return package_file(*reader); }
  tileformat::AnalysisMetadata meta;
  tileformat::Tiling tiling;
  int block_size = 0, min_zoom = 0, max_zoom = 0;
};

// Throws InputError naming the file if it is missing, not a package, or not
// an analysis package.
AnalysisPackage open_analysis_package(const std::string& path);

}  // namespace globe
