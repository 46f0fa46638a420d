// `globe-vectorize export AREAS --format mvt` (docs/areas.md "Web maps"): an
// area package as Mapbox Vector Tiles 2.1, one MVT layer per source layer,
// each feature's polygons in a tile one POLYGON or MULTIPOLYGON with its id,
// class, attributes and choropleth value (web/area_mvt.hpp); tiles gzipped.
// Optionally a MapLibre style with fills (the choropleth as a step
// expression) under outlines.
#pragma once

#include "export/mvt_export.hpp"
#include "kit/progress.hpp"

namespace globe {

MvtExportSummary export_area_mvt(const MvtExportSettings& s, Progress& progress);

}  // namespace globe
