// The package kinds' descriptors (see package_kinds.hpp).
#include "tileformat/package_kinds.hpp"

#include "tileformat/image_tile.hpp"

namespace tileformat {

namespace {
// describe() indexes the table by the enumerator.
consteval bool rows_in_kind_order() {
  for (size_t i = 0; i < std::size(kPackageKinds); ++i)
    if (static_cast<size_t>(kPackageKinds[i].kind) != i) return false;
  return true;
}
static_assert(rows_in_kind_order(), "kPackageKinds rows must follow PackageKind's order");
}  // namespace

std::span<const PackageKindDescriptor> package_kinds() {
  return kPackageKinds;
}

const PackageKindDescriptor& describe(PackageKind kind) {
  return kPackageKinds[static_cast<size_t>(kind)];
}

bool is_format_of(const PackageKindDescriptor& kind, const std::string& format) {
  return kind.format ? format == kind.format : parse_image_format(format).has_value();
}

std::optional<PackageKind> package_kind_of_format(const std::string& format) {
  for (const PackageKindDescriptor& d : kPackageKinds)
    if (is_format_of(d, format)) return d.kind;
  return std::nullopt;
}

const char* package_kind_name(PackageKind kind) {
  return describe(kind).name;
}

}  // namespace tileformat
