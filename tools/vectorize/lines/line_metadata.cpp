// Line package metadata (see line_metadata.hpp).
#include "lines/line_metadata.hpp"

#include "tileformat/line_tile.hpp"

namespace globe {

tileformat::LineMetadata line_metadata(const LinesSettings& s, const VectorFrame& frame,
                                       const LinePlan& plan, const LineClasses& classes,
                                       const LineFacts& facts) {
  tileformat::LineMetadata m;
  m.common =
      vector_common_metadata(s, "Line clusters", tileformat::kLineClustersFormat, frame,
                             plan.tiling, facts.extent, plan.area, plan.min_zoom, plan.max_zoom);
  m.extent = s.extent;
  m.cluster_grid = s.cluster_grid;
  m.simplify_px = s.simplify_px;
  m.tile_px = kLineTilePx;
  m.features = facts.features;
  m.classes_json = classes.json();
  for (size_t i = 0; i < facts.layers.size(); ++i)
    m.layers.push_back({facts.layers[i].name, facts.layers[i].source, facts.layer_features[i]});
  return m;
}

}  // namespace globe
