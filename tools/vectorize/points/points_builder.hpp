// Builds a point package (docs/points.md) for charts:
//   1. read:      places are read (OGR point layers, CSV with --xy), checked
//                 (numeric values, no negative ones unless --signed),
//                 projected into the tiling CRS and kept in memory; their
//                 attributes go to the package's features table.
//   2. aggregate: from the finest zoom to the coarsest, places closer than
//                 --merge-px pixels of the zoom become one
//                 (point_aggregation.hpp), each zoom from the next finer.
//   3. encode:    each zoom's places are grouped by tile; each tile gets its
//                 cluster grid, is encoded and written.
// Memory: about 80 + 16 x fields bytes per place (two zooms at a time).
// Output is identical for any -j.
#pragma once

#include "kit/package_output.hpp"

#include <cstdint>

#include "kit/progress.hpp"
#include "points/points_settings.hpp"

namespace globe {

struct PointsSummary : PackageSummary {
  uint64_t features_read = 0, places = 0;
  uint64_t skipped_no_point = 0;     // features without a point (empty geometry)
  uint64_t skipped_unprojected = 0;  // outside the tiling or not transformable
  uint64_t skipped_outside = 0;      // outside --bbox
  uint64_t empty_values = 0;         // null values read as 0
  uint64_t coarsest_places = 0;      // places at the coarsest zoom
  uint64_t peak_merge_places = 0;    // the most places a merge held at once
  int min_zoom = 0, max_zoom = 0;
};

PointsSummary build_points(const PointsSettings& settings, Progress& progress);

}  // namespace globe
