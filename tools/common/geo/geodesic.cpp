// Geodesic distances and lines (see geodesic.hpp).
#include "geo/geodesic.hpp"

#include <geodesic.h>

#include <algorithm>
#include <cmath>

namespace globe {

namespace {

const geod_geodesic& wgs84() {
  static const geod_geodesic g = [] {
    geod_geodesic e;
    geod_init(&e, 6378137.0, 1 / 298.257223563);
    return e;
  }();
  return g;
}

}  // namespace

double geodesic_distance_m(double lon1, double lat1, double lon2, double lat2) {
  double s12 = 0;
  geod_inverse(&wgs84(), lat1, lon1, lat2, lon2, &s12, nullptr, nullptr);
  return s12;
}

std::vector<std::pair<double, double>> geodesic_points(double lon1, double lat1, double lon2,
                                                       double lat2, double step_m) {
  geod_geodesicline line;
  // GEOD_DISTANCE for the line's length (s13, else NaN: the line was drawn
  // as one straight step, found by clang's UBSan at the NaN's cast) and
  // GEOD_DISTANCE_IN for positions by distance (else NaN too).
  geod_inverseline(&line, &wgs84(), lat1, lon1, lat2, lon2,
                   GEOD_LATITUDE | GEOD_LONGITUDE | GEOD_DISTANCE | GEOD_DISTANCE_IN);
  const double length = line.s13;
  const int steps = std::max(1, static_cast<int>(std::ceil(length / std::max(step_m, 1.0))));
  std::vector<std::pair<double, double>> out;
  out.reserve(size_t(steps) + 1);
  out.emplace_back(lon1, lat1);
  for (int i = 1; i < steps; ++i) {
    double lat = 0, lon = 0;
    geod_genposition(&line, GEOD_LONG_UNROLL, length * i / steps, &lat, &lon, nullptr, nullptr,
                     nullptr, nullptr, nullptr, nullptr);
    out.emplace_back(lon, lat);
  }
  // The end, unrolled like the rest.
  double end_lon = lon2;
  while (steps > 1 && end_lon - out.back().first > 180)
    end_lon -= 360;
  while (steps > 1 && end_lon - out.back().first < -180)
    end_lon += 360;
  if (steps == 1) end_lon = lon1 + std::remainder(lon2 - lon1, 360.0);
  out.emplace_back(end_lon, lat2);
  return out;
}

}  // namespace globe
