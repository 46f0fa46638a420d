// Builds a line-cluster package (docs/lines.md "Pipeline") in three passes:
//   1. read:   features are read (OGR), classed, projected into the tiling CRS
//              and appended to a scratch geometry file; attributes go to the
//              package's features table. Extent and segment lengths are
//              gathered for the tiling and the default zoom range.
//   2. cut:    each feature is simplified and cut into the tiles of every
//              zoom; the pieces go to an external sort (spilling to disk past
//              --memory-mb).
//   3. encode: pieces come back grouped by tile; each tile gets its cluster
//              grid, is encoded and written.
// Parallel work is done in batches consumed in order, so output is identical
// for any -j.
#pragma once

#include "kit/package_output.hpp"

#include <cstdint>

#include "kit/progress.hpp"
#include "lines/lines_settings.hpp"

namespace globe {

struct LinesSummary : PackageSummary {
  uint64_t features_read = 0, features_kept = 0, features_skipped = 0;
  uint64_t bad_parts = 0;  // NaN, degenerate or untransformable parts
  uint64_t antimeridian_cuts = 0;
  uint64_t segments = 0, max_zoom_segments = 0, points = 0;
  uint64_t spilled_runs = 0, spilled_bytes = 0;
  int min_zoom = 0, max_zoom = 0;
};

LinesSummary build_lines(const LinesSettings& settings, Progress& progress);

}  // namespace globe
