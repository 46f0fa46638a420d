// Opening analysis packages (see analysis_package.hpp).
#include "runtime/analysis_package.hpp"

#include "runtime/package_open.hpp"

namespace globe {

AnalysisPackage open_analysis_package(const std::string& path) {
  AnalysisPackage p;
  p.reader = open_package_of_kind(path, tileformat::PackageKind::kAnalysis);
  p.meta =
      read_metadata(path, [&] { return tileformat::read_analysis_metadata(p.reader->metadata()); });
  p.tiling = p.meta.common.tiling;
  p.block_size = p.meta.block_size;
  p.min_zoom = p.meta.common.min_zoom;
  p.max_zoom = p.meta.common.max_zoom;
  return p;
}

}  // namespace globe
