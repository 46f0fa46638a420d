// Builds an area package (docs/areas.md "Pipeline") in three passes:
//   1. read:   polygons are read (OGR), projected into the tiling CRS (cut at
//              the antimeridian, closed over a pole), repaired where invalid
//              (GEOS MakeValid, counted) and appended to a scratch file;
//              attributes go to the features table, choropleth values are
//              kept for the classes.
//   2. cut:    per zoom, each feature is snapped to the zoom's grid and
//              clipped to its tiles (area_tiles.hpp); the pieces go to an
//              external sort (spilling to disk past --memory-mb).
//   3. encode: pieces come back grouped by tile and are encoded and written.
// Output is identical for any -j.
#pragma once

#include <cstdint>

#include "areas/areas_settings.hpp"
#include "kit/package_output.hpp"
#include "kit/progress.hpp"

namespace globe {

struct AreasSummary : PackageSummary {
  uint64_t features_read = 0, features_kept = 0, features_skipped = 0;
  uint64_t bad_rings = 0;  // rings with NaN, too few vertices, or that cannot be transformed
  uint64_t repaired = 0;   // features GEOS MakeValid repaired
  uint64_t antimeridian_cuts = 0, polygons = 0, vertices = 0, max_zoom_vertices = 0;
  uint64_t dropped_small = 0, no_data = 0;
  uint64_t spilled_runs = 0, spilled_bytes = 0;
  int min_zoom = 0, max_zoom = 0;
};

AreasSummary build_areas(const AreasSettings& settings, Progress& progress);

}  // namespace globe
