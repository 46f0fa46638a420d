// Plane geometry of the area pipeline (docs/areas.md "Tiles"), free of GDAL:
// lon/lat polygons made ready for a global tiling (the antimeridian and the
// poles), and a polygon snapped to a zoom's grid - the simplification that
// keeps shared borders shared: neighbours hold the same source vertices, so
// they snap to the same grid points and their borders stay identical at
// every zoom (no gap, no overlap), where Douglas-Peucker run per polygon
// would move each side differently.
#pragma once

#include <cstdint>
#include <vector>

#include "geo/geos_polygons.hpp"
#include "lines/line_geometry.hpp"
#include "tileformat/tiling.hpp"

namespace globe {

// A polygon's rings as read (exterior first; closed or open).
using SourceRings = std::vector<std::vector<XY>>;

// Twice the signed area (shoelace) of a ring.
double ring_area2(const PlaneRing& r);

// Drops a closing repeat of the first point and consecutive repeats; false
// if a coordinate is not finite.
bool clean_ring(PlaneRing& r);

// A lon/lat polygon as pieces within longitudes [-180, 180]: each ring is
// unwrapped where consecutive vertices lie more than 180 degrees apart; an
// exterior ring that goes once around a pole is closed through that pole;
// what then lies beyond +-180 degrees is moved a turn back (clipped by
// GEOS). `cuts` counts polygons that crossed the antimeridian.
PlaneMultiPolygon wrap_lonlat_polygon(const PlanePolygon& lonlat, Geos& geos, uint64_t& cuts);

// Exterior rings positive (ring_area2 with y down), holes negative.
void orient_for_tiles(PlaneMultiPolygon& m);

// The polygons (global grid units of zoom z: x east, y south from the
// tiling's top-left, `extent` units a tile) with every vertex snapped to a
// multiple of `step`, repeats and spikes removed, rings left without area
// dropped; a polygon whose exterior collapsed is dropped too (counted in
// `dropped`) unless `keep_collapsed`: then it becomes the one grid cell
// around its first vertex, so the finest zoom loses no feature.
PlaneMultiPolygon snap_polygons(const PlaneMultiPolygon& grid, double step, bool keep_collapsed,
                                uint64_t& dropped);

// Frame (tiling CRS) coordinates to zoom z's global grid units.
PlaneMultiPolygon to_zoom_grid(const PlaneMultiPolygon& frame, const tileformat::Tiling& t, int z,
                               int extent);

}  // namespace globe
