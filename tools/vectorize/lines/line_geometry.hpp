// Plane geometry of the line pipeline, free of GDAL and of the tile format:
// cleaning parts, Douglas-Peucker simplification, segment clipping and
// splitting lon/lat lines at the antimeridian.
#pragma once

#include <span>
#include <vector>

#include "tileformat/tiling.hpp"

namespace globe {

struct XY {
  double x = 0, y = 0;
  bool operator==(const XY&) const = default;
};

enum class PartStatus { kOk, kNonFinite, kDegenerate };

// Drops consecutive repeated vertices; a part with a NaN/Inf coordinate is
// kNonFinite, one with fewer than two distinct vertices kDegenerate.
PartStatus clean_part(std::vector<XY>& part);

// Distance from p to segment ab.
double segment_distance(XY p, XY a, XY b);

// Douglas-Peucker: keeps the end points and every vertex needed to stay
// within `tolerance` of the input. Deterministic; iterative (no recursion).
std::vector<XY> douglas_peucker(std::span<const XY> in, double tolerance);

// Liang-Barsky: clips segment ab to `box` in place; false if it misses it.
// Parameters t0, t1 (0..1) say where the clipped ends lie on the input.
bool clip_segment(XY& a, XY& b, const tileformat::Bounds& box, double* t0 = nullptr,
                  double* t1 = nullptr);

// Longitudes wrapped into [-180, 180]; where consecutive vertices are more
// than 180 degrees apart the line crosses the antimeridian: it is cut there
// (the crossing latitude interpolated) and continues on the other side.
std::vector<std::vector<XY>> split_antimeridian(std::span<const XY> lonlat);

}  // namespace globe
