// Opening point packages (see point_package.hpp).
#include "runtime/point_package.hpp"

#include "runtime/package_open.hpp"

namespace globe {

PointPackage open_point_package(const std::string& path) {
  PointPackage p;
  p.reader = open_package_of_kind(path, tileformat::PackageKind::kPoints);
  p.meta =
      read_metadata(path, [&] { return tileformat::read_point_metadata(p.reader->metadata()); });
  return p;
}

}  // namespace globe
