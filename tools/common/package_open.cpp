// Opening packages for inspection (see package_open.hpp).
#include "package_open.hpp"

#include "errors.hpp"
#include "tileformat/error.hpp"

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

std::unique_ptr<tileformat::PackageReader> open_package_of_format(const std::string& path,
                                                                  const std::string& format,
                                                                  const std::string& kind) {
  std::unique_ptr<tileformat::PackageReader> reader = open_package(path);
  const std::string fmt = package_format(*reader, path);
  if (fmt != format)
    throw InputError(path + ": a '" + fmt + "' package, not a " + kind + " package (" + format +
                     ")");
  return reader;
}

double meta_number(const tileformat::PackageReader& reader, const std::string& path,
                   const std::string& key) {
  auto v = reader.meta(key);
  if (!v) throw InputError(path + ": metadata key " + key + " is missing (tileformat §3.2)");
  try {
    return std::stod(*v);
  } catch (const std::exception&) {
    throw InputError(path + ": metadata key " + key + " is not a number (tileformat §3.2)");
  }
}

tileformat::Tiling meta_tiling(const tileformat::PackageReader& reader, const std::string& path) {
  try {
    return tileformat::Tiling::from_metadata(reader.metadata());
  } catch (const tileformat::FormatError& e) {
    throw InputError(path + ": " + e.what());
  }
}

}  // namespace globe
