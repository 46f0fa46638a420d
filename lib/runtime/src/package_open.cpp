// Opening packages for inspection (see package_open.hpp).
#include "runtime/package_open.hpp"

namespace globe {

std::unique_ptr<tileformat::PackageReader> open_package(const std::string& path) {
  try {
    return std::make_unique<tileformat::PackageReader>(path);
  } catch (const tileformat::PackageError& e) {
    throw InputError(e.what());
  }
}

std::string package_format(const tileformat::PackageReader& reader, const std::string& path) {
  const auto fmt = reader.meta("format");
  if (!fmt) throw InputError(path + ": metadata has no 'format'; not a globe package");
  return *fmt;
}

std::optional<tileformat::PackageKind> package_kind(const std::string& path) {
  return tileformat::package_kind_of_format(package_format(*open_package(path), path));
}

std::unique_ptr<tileformat::PackageReader> open_package_of_kind(const std::string& path,
                                                                tileformat::PackageKind kind) {
  std::unique_ptr<tileformat::PackageReader> reader = open_package(path);
  const std::string fmt = package_format(*reader, path);
  if (tileformat::package_kind_of_format(fmt) != kind) {
    const std::string expected =
        kind == tileformat::PackageKind::kTerrain    ? tileformat::kMBlockFormat
        : kind == tileformat::PackageKind::kLines    ? std::string(tileformat::kLineClustersFormat)
        : kind == tileformat::PackageKind::kAnalysis ? std::string(tileformat::kAnalysisFormat)
        : kind == tileformat::PackageKind::kPoints   ? std::string(tileformat::kPointsFormat)
                                                     : std::string("png, jpg, webp");
    const std::string name = tileformat::package_kind_name(kind);
    throw InputError(
        path + ": a '" + fmt + "' package, not " +
        (kind == tileformat::PackageKind::kImage || kind == tileformat::PackageKind::kAnalysis
             ? "an "
             : "a ") +
        name + " package (" + expected + ")");
  }
  return reader;
}

}  // namespace globe
