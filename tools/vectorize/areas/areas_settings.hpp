// Settings of `globe-vectorize areas`, filled by the command-line parser and
// read by the builder (nothing here touches OGR or GEOS). The line options
// they share (layers, --where, classes and styles, zooms, --memory-mb) keep
// their meaning; --simplify is the snapping grid of a zoom.
#pragma once

#include <string>

#include "areas/choropleth.hpp"
#include "lines/lines_settings.hpp"

namespace globe {

struct ChoroplethSettings {
  std::string field, denominator;  // --choropleth FIELD[/DENOMINATOR]
  int classes = 5;
  ClassMethod method = ClassMethod::kQuantile;
  std::string colors = "YlOrRd";
  std::string no_data_color = "#cccccc";
};

struct AreasSettings : LinesSettings {
  AreasSettings() { simplify_px = 0.5; }
  int buffer_px = 4;  // how far polygons reach past a tile's edge, in px of a 256 px tile
  std::optional<ChoroplethSettings> choropleth;
};

}  // namespace globe
