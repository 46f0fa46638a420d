// Opening an existing package of one kind for inspection: errors name the
// file and say what the package is instead (tileformat §3.2).
#pragma once

#include <memory>
#include <string>

#include "tileformat/package.hpp"
#include "tileformat/tiling.hpp"

namespace globe {

// Throws InputError if `path` is missing or not a package.
std::unique_ptr<tileformat::PackageReader> open_package(const std::string& path);
// The package's `format` metadata value; throws InputError if it has none.
std::string package_format(const tileformat::PackageReader& reader, const std::string& path);
// Throws InputError if `path` is missing, not a package, or its `format` is
// not `format`.
std::unique_ptr<tileformat::PackageReader> open_package_of_format(const std::string& path,
                                                                  const std::string& format,
                                                                  const std::string& kind);
// A numeric metadata value; throws InputError if missing or not a number.
double meta_number(const tileformat::PackageReader& reader, const std::string& path,
                   const std::string& key);
// The package's tiling; throws InputError.
tileformat::Tiling meta_tiling(const tileformat::PackageReader& reader, const std::string& path);

}  // namespace globe
