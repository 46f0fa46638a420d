// Opening area packages (see area_package.hpp).
#include "runtime/area_package.hpp"

#include "runtime/errors.hpp"
#include "runtime/package_open.hpp"

namespace globe {

AreaPackage open_area_package(const std::string& path) {
  AreaPackage p;
  p.reader = open_package_of_kind(path, tileformat::PackageKind::kAreas);
  p.meta =
      read_metadata(path, [&] { return tileformat::read_area_metadata(p.reader->metadata()); });
  p.classes =
      parse_classes_json(p.meta.classes_json, path + ": metadata globe:classes (tileformat §12.3)");
  return p;
}

}  // namespace globe
