// Projects feature geometry from a layer's CRS into the tiling CRS. For the
// global tilings lines go through longitude/latitude first, where they are
// cut at the antimeridian; web mercator clamps latitude to its +-85.0511.
#pragma once

#include <memory>
#include <vector>

#include "geo/spatial_ref.hpp"
#include "lines/line_geometry.hpp"

namespace globe {

enum class TargetFrame { kWebMercator, kGeodetic, kProjected };

struct ProjectionCounts {
  uint64_t failed_parts = 0;      // PROJ could not transform a vertex
  uint64_t nonfinite_parts = 0;   // NaN / Inf coordinates in the input
  uint64_t degenerate_parts = 0;  // fewer than two distinct vertices
  uint64_t antimeridian_cuts = 0;
};

class LineProjector {
 public:
  // `target` is used for kProjected only.
  LineProjector(TargetFrame frame, const SpatialRef& source, const SpatialRef* target);

  // Appends the projected, cleaned parts of `in` to `out`.
  void project_lines(const std::vector<std::vector<XY>>& in, std::vector<std::vector<XY>>& out,
                     ProjectionCounts& counts) const;
  // False if the point cannot be projected.
  bool project_point(XY in, XY& out) const;
  // A polygon ring into longitude/latitude (the global frames; not cut at
  // the antimeridian, not yet in the frame: lonlat_to_frame does that) or
  // into the target CRS (kProjected). False if a vertex cannot be
  // transformed, is not finite, or lies off the globe.
  bool transform_ring(std::vector<XY>& ring) const;
  TargetFrame frame() const { return frame_; }
  // Longitude/latitude (degrees) of a tiling-CRS position (for bounds).
  static XY frame_to_lonlat(TargetFrame frame, XY p);
  static XY lonlat_to_frame(TargetFrame frame, XY p);

 private:
  bool transform(std::vector<XY>& pts) const;
  TargetFrame frame_;
  std::unique_ptr<CoordTransform> to_frame_;  // to lon/lat (global) or to the target
};

}  // namespace globe
