// Inspection of point packages (see points_inspect.cpp): `globe-vectorize
// info`, `validate` and `extract` hand point packages to these.
#pragma once

#include <cstdint>
#include <string>

#include "io/vector_writer.hpp"

namespace globe {

// Prints metadata and per-zoom counts on stdout; returns the exit code.
int points_info(const std::string& path, bool json);
// Prints the report on stdout; returns 0 valid, 5 warnings only, 1 errors.
int points_validate(const std::string& path);
// Adds zoom `zoom`'s places to `out` (layer "places"); returns how many.
// Throws UsageError for a zoom the package does not hold.
uint64_t points_extract(const std::string& path, int zoom, VectorWriter& out);

}  // namespace globe
