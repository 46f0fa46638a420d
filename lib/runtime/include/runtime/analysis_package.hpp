// Opening an existing analysis package (tileformat §9) for inspection and
// drawing: the reader plus its metadata, checked once.
#pragma once

#include <memory>
#include <string>

#include "tileformat/metadata.hpp"
#include "tileformat/package.hpp"

namespace globe {

struct AnalysisPackage {
  std::unique_ptr<tileformat::PackageReader> reader;
  tileformat::AnalysisMetadata meta;
  tileformat::Tiling tiling;
  int block_size = 0, min_zoom = 0, max_zoom = 0;
};

// Throws InputError naming the file if it is missing, not a package, or not
// an analysis package.
AnalysisPackage open_analysis_package(const std::string& path);

}  // namespace globe
