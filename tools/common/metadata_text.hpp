// Numbers as package metadata writes them (bounds, center, steps).
#pragma once

#include <string>

#include "tileformat/tiling.hpp"

namespace globe {

// `v` with `digits` significant digits; digits = 0: the shortest text that
// reads back as exactly `v` (bounds: clamped values must stay in range).
std::string metadata_number(double v, int digits = 10);

// The `bounds` value "west,south,east,north": each number with `digits`
// significant digits (0: exact), then clamped to `limits` (the tiling's
// lon/lat range), so that rounding never takes it past what readers accept.
std::string metadata_bounds(const tileformat::Bounds& lonlat, const tileformat::Bounds& limits,
                            int digits);

}  // namespace globe
