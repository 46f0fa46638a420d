// The one wrapper of GEOS (its C API, Debian's libgeos-dev) the tools use:
// polygons in a plane - validity, repair (MakeValid), clipping to a box and
// the polygon's pole of inaccessibility. Polygons cross this boundary as
// plain rings of points; no GEOS type leaves this file. One Geos per thread
// (a GEOS context is not shared).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

namespace globe {

struct PlanePoint {
  double x = 0, y = 0;
  bool operator==(const PlanePoint&) const = default;
};
// A ring is open: its first point is not repeated at its end.
using PlaneRing = std::vector<PlanePoint>;
// The exterior ring, then the holes.
using PlanePolygon = std::vector<PlaneRing>;
using PlaneMultiPolygon = std::vector<PlanePolygon>;

class Geos {
 public:
  Geos();
  ~Geos();
  Geos(const Geos&) = delete;
  Geos& operator=(const Geos&) = delete;

  // OGC validity (no self-intersection, holes inside their shell, ...).
  bool is_valid(const PlaneMultiPolygon& m);
  // The polygonal part of GEOS MakeValid ("structure" method, collapsed
  // parts dropped): valid, covering what the rings enclose.
  PlaneMultiPolygon make_valid(const PlaneMultiPolygon& m);
  // The intersection with the box [x0, x1] x [y0, y1] (valid for valid input).
  PlaneMultiPolygon clip(const PlaneMultiPolygon& m, double x0, double y0, double x1, double y1);
  struct Box {
    double x0, y0, x1, y1;
  };
  // m cut to each box by GEOS's rectangle clipping (converted to GEOS once;
  // fast, but a piece may touch itself along the box's edge: check it).
  // Where the result disagrees with m about a box corner (rectangle
  // clipping turned a ring inside out), the overlay intersection is used.
  std::vector<PlaneMultiPolygon> clip_to_boxes(const PlaneMultiPolygon& m,
                                               const std::vector<Box>& boxes);
  // How often clip_to_boxes fell back to the overlay.
  uint64_t overlay_fallbacks() const { return overlay_fallbacks_; }
  // The centre of the largest circle inside the polygon (the pole of
  // inaccessibility), to `tolerance`.
  PlanePoint inscribed_centre(const PlanePolygon& p, double tolerance);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  uint64_t overlay_fallbacks_ = 0;
};

}  // namespace globe
