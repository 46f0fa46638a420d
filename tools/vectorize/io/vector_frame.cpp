// Vector frames and tilings (see vector_frame.hpp).
#include "io/vector_frame.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "runtime/errors.hpp"
#include "tileformat/package.hpp"

namespace globe {

using tileformat::Bounds;
using tileformat::Tiling;

VectorFrame choose_vector_frame(const std::string& like, const BuildOptions& o) {
  VectorFrame f;
  if (!like.empty()) {
    tileformat::PackageReader reader(like);
    f.tiling = Tiling::from_metadata(reader.metadata());
    if (f.tiling->scheme == tileformat::Scheme::kLocal) {
      f.frame = TargetFrame::kProjected;
      f.target = SpatialRef::from_wkt(f.tiling->crs, like);
    } else {
      f.frame = f.tiling->scheme == tileformat::Scheme::kGeodetic ? TargetFrame::kGeodetic
                                                                  : TargetFrame::kWebMercator;
    }
    return f;
  }
  if (o.tiling == tileformat::Scheme::kWebMercator) {
    f.frame = TargetFrame::kWebMercator;
    f.tiling = Tiling::webmercator();
  } else if (o.tiling == tileformat::Scheme::kGeodetic) {
    f.frame = TargetFrame::kGeodetic;
    f.tiling = Tiling::geodetic();
  } else {
    f.frame = TargetFrame::kProjected;
    if (!o.t_srs.empty()) f.target = SpatialRef::from_user_input(o.t_srs, "--t_srs");
  }
  if (!o.t_srs.empty() && f.frame != TargetFrame::kProjected)
    throw UsageError("--t_srs applies to --tiling local only");
  return f;
}

Tiling frame_tiling(const VectorFrame& frame, const Bounds& extent) {
  if (frame.tiling) return *frame.tiling;
  const double span = std::max({extent.width(), extent.height(), 1e-9});
  const double root = std::exp2(std::ceil(std::log2(span)));
  return Tiling::local(frame.target->wkt2(), extent.min_x, extent.max_y, root);
}

Bounds frame_area(const VectorFrame& frame, const Tiling& tiling, const BuildOptions& o) {
  Bounds area = tiling.extent();
  if (!o.bbox) return area;
  const auto& b = *o.bbox;
  Bounds box;
  if (frame.frame == TargetFrame::kProjected) {
    CoordTransform t(SpatialRef::from_user_input("EPSG:4326", "--bbox"), *frame.target);
    if (!t.transform_bounds({b[0], b[1], b[2], b[3]}, box))
      throw UsageError("--bbox cannot be expressed in the tiling CRS");
  } else {
    const XY lo = LineProjector::lonlat_to_frame(frame.frame, {b[0], b[1]});
    const XY hi = LineProjector::lonlat_to_frame(frame.frame, {b[2], b[3]});
    box = {lo.x, lo.y, hi.x, hi.y};
  }
  return {std::max(area.min_x, box.min_x), std::max(area.min_y, box.min_y),
          std::min(area.max_x, box.max_x), std::min(area.max_y, box.max_y)};
}

tileformat::CommonMetadata vector_common_metadata(const BuildOptions& o, const char* what,
                                                  const char* format, const VectorFrame& frame,
                                                  const Tiling& tiling, const Bounds& e,
                                                  const Bounds& a, int min_zoom, int max_zoom) {
  // The data's bounds, clipped to the area, in longitude/latitude.
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
  tileformat::CommonMetadata c;
  for (const auto& input : o.inputs) {
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(input, ec);
    c.inputs.push_back({input, ec ? 0 : static_cast<uint64_t>(bytes)});
  }
  c.name = std::filesystem::path(o.output).stem().string();
  c.format = format;
  c.type = "overlay";
  c.description = tileformat::build_description(what, "globe-vectorize", c.inputs);
  c.lonlat = ll;
  c.min_zoom = min_zoom;
  c.max_zoom = max_zoom;
  c.center_zoom = tiling.view_zoom(b, min_zoom, max_zoom);
  c.tiling = tiling;
  c.generator = "globe-vectorize " GLOBE_VERSION;
  c.command_line = o.command_line;
  return c;
}

}  // namespace globe
