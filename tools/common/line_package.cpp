// Opening line-cluster packages (see line_package.hpp).
#include "line_package.hpp"

#include <cpl_json.h>

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
  CPLJSONDocument doc;
  const auto classes = p.reader->meta("globe:classes");
  if (!classes || !doc.LoadMemory(*classes) ||
      doc.GetRoot().GetType() != CPLJSONObject::Type::Array)
    throw InputError(path +
                     ": metadata globe:classes is missing or not a JSON array (tileformat §7.4)");
  const CPLJSONArray arr = doc.GetRoot().ToArray();
  for (int i = 0; i < arr.Size(); ++i)
    p.class_names.push_back(arr[i].GetString("name"));
  return p;
}

}  // namespace globe
