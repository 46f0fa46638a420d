// Slope, aspect and curvature of one sample from its 3 x 3 neighbourhood,
// and the true ground distance between samples of each tiling. Pure
// arithmetic, no I/O (the formulas: docs/analysis.md).
#pragma once

#include <cstdint>

#include "tileformat/tiling.hpp"

namespace globe {

// Heights of the window, row-major from the north-west: z[0] z[1] z[2] is the
// north row. Missing neighbours are replaced by the centre (as gdaldem
// -compute_edges does).
struct Window3 {
  double z[9];
};

struct Derivatives {
  double slope_deg = 0;   // Horn (1981), as gdaldem slope
  double aspect_deg = 0;  // clockwise from north, the direction the slope faces; NaN on flats
  double profile = 0;     // 1/m; > 0 convex along the slope line; NaN on flats
  double plan = 0;        // 1/m; > 0 convex across it (ridges); NaN on flats
};

// dx, dy: metres between samples east-west and north-south at this sample.
Derivatives derivatives(const Window3& w, double dx, double dy);

// Ground metres between neighbouring samples of row `row` (0 = north edge)
// of the blocks in tile row `tile_y` at zoom z (steps samples per tile):
// local tilings are in metres; geodetic and webmercator use the WGS84
// ellipsoid's radii of curvature at the row's latitude.
struct GroundSpacing {
  double dx = 0, dy = 0;
};
GroundSpacing ground_spacing(const tileformat::Tiling& tiling, int z, int steps, uint32_t tile_y,
                             int row);
// The same at the tiling's CRS y `crs_y` (any y, not only a row's).
GroundSpacing ground_spacing_at(const tileformat::Tiling& tiling, int z, int steps, double crs_y);

}  // namespace globe
