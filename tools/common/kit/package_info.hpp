// The part of `info` every package kind shares: file size, metadata (long
// values shortened) and the per-zoom tile table, printed on stdout.
#pragma once

#include <string>

#include "tileformat/package.hpp"

namespace globe {

void print_package_info(tileformat::PackageReader& reader, const std::string& path);

}  // namespace globe
