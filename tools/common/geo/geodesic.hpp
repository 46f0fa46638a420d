// Distances and lines on the WGS84 ellipsoid (PROJ's geodesic routines,
// Karney 2013): the one place the tools call them.
#pragma once

#include <utility>
#include <vector>

namespace globe {

// Metres along the shortest path on the ellipsoid between two points given
// in degrees of longitude and latitude.
double geodesic_distance_m(double lon1, double lat1, double lon2, double lat2);

// Points along that shortest path, both ends included, at most `step_m`
// apart, as (longitude, latitude). Longitudes are unrolled: they change
// continuously from lon1 (a path across the antimeridian goes past +-180).
std::vector<std::pair<double, double>> geodesic_points(double lon1, double lat1, double lon2,
                                                       double lat2, double step_m);

}  // namespace globe
