// Line package metadata (see line_metadata.hpp).
#include "line_metadata.hpp"

#include <algorithm>
#include <filesystem>

#include "tileformat/line_tile.hpp"

namespace globe {

using tileformat::Bounds;

tileformat::LineMetadata line_metadata(const LinesSettings& s, const LineFrame& frame,
                                       const LinePlan& plan, const LineClasses& classes,
                                       const LineFacts& facts) {
  // Longitude/latitude bounds of the data (clipped to the area).
  const Bounds& e = facts.extent;
  const Bounds& a = plan.area;
  const Bounds b{std::max(e.min_x, a.min_x), std::max(e.min_y, a.min_y), std::min(e.max_x, a.max_x),
                 std::min(e.max_y, a.max_y)};
  Bounds ll;
  if (frame.frame == TargetFrame::kProjected) {
    CoordTransform t(*frame.target, SpatialRef::from_user_input("EPSG:4326", "bounds"));
    if (!t.transform_bounds(b, ll)) ll = {-180, -85, 180, 85};
  } else {
    const XY lo = LineProjector::frame_to_lonlat(frame.frame, {b.min_x, b.min_y});
    const XY hi = LineProjector::frame_to_lonlat(frame.frame, {b.max_x, b.max_y});
    ll = {lo.x, lo.y, hi.x, hi.y};
  }
  tileformat::LineMetadata m;
  tileformat::CommonMetadata& c = m.common;
  for (const auto& input : s.inputs) {
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(input, ec);
    c.inputs.push_back({input, ec ? 0 : static_cast<uint64_t>(bytes)});
  }
  c.name = std::filesystem::path(s.output).stem().string();
  c.format = tileformat::kLineClustersFormat;
  c.type = "overlay";
  c.description = tileformat::build_description("Line clusters", "globe-vectorize", c.inputs);
  c.lonlat = ll;
  c.min_zoom = plan.min_zoom;
  c.max_zoom = plan.max_zoom;
  c.center_zoom = plan.tiling.view_zoom(b, plan.min_zoom, plan.max_zoom);
  c.tiling = plan.tiling;
  c.generator = "globe-vectorize " GLOBE_VERSION;
  c.command_line = s.command_line;
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
