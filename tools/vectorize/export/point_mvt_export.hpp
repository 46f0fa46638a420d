// `globe-vectorize export POINTS --format mvt` (docs/web.md "Vector tiles"): a
// point package as Mapbox Vector Tiles 2.1, one MVT layer "points", each place
// of a tile a POINT with its id (an aggregate's: the smallest of its places),
// "count" (the source places it stands for) and one number per field of the
// package (sums or means, as its globe:aggregate says); tiles gzipped.
// Optionally a MapLibre style drawing the places as circles sized by count.
#pragma once

#include "export/mvt_export.hpp"
#include "kit/progress.hpp"

namespace globe {

MvtExportSummary export_point_mvt(const MvtExportSettings& s, Progress& progress);

}  // namespace globe
