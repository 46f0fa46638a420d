// Opening line-cluster packages (see line_package.hpp).
#include "line_package.hpp"

#include "errors.hpp"
#include "package_open.hpp"
#include "tileformat/line_tile.hpp"

namespace globe {

LinePackage open_line_package(const std::string& path) {
  LinePackage p;
  p.reader = open_package_of_format(path, tileformat::kLineClustersFormat, "line-cluster");
  p.tiling = meta_tiling(*p.reader, path);
  p.extent = static_cast<int>(meta_number(*p.reader, path, "globe:extent"));
  p.cluster_grid = static_cast<int>(meta_number(*p.reader, path, "globe:cluster_grid"));
  p.min_zoom = static_cast<int>(meta_number(*p.reader, path, "minzoom"));
  p.max_zoom = static_cast<int>(meta_number(*p.reader, path, "maxzoom"));
  const auto classes = p.reader->meta("globe:classes");
  if (!classes) throw InputError(path + ": metadata globe:classes is missing (tileformat §7.4)");
  p.classes = parse_classes_json(*classes, path + ": metadata globe:classes (tileformat §7.4)");
  return p;
}

}  // namespace globe
