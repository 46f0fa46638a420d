// Opening line-cluster packages (see line_package.hpp).
#include "runtime/line_package.hpp"

#include "runtime/errors.hpp"
#include "runtime/package_open.hpp"
#include "tileformat/line_tile.hpp"

namespace globe {

LinePackage open_line_package(const std::string& path) {
  LinePackage p;
  p.reader = open_package_of_kind(path, tileformat::PackageKind::kLines);
  p.meta =
      read_metadata(path, [&] { return tileformat::read_line_metadata(p.reader->metadata()); });
  p.tiling = p.meta.common.tiling;
  p.extent = p.meta.extent;
  p.cluster_grid = p.meta.cluster_grid;
  p.min_zoom = p.meta.common.min_zoom;
  p.max_zoom = p.meta.common.max_zoom;
  p.classes =
      parse_classes_json(p.meta.classes_json, path + ": metadata globe:classes (tileformat §7.4)");
  return p;
}

}  // namespace globe
