// GEOS wrapper (see geos_polygons.hpp).
#include "geo/geos_polygons.hpp"

#include <geos_c.h>

#include <stdexcept>
#include <string>
#include <utility>

namespace globe {
namespace {

void on_message(const char* message, void* user) {
  *static_cast<std::string*>(user) = message;
}

}  // namespace

struct Geos::Impl {
  GEOSContextHandle_t ctx = GEOS_init_r();
  std::string error;

  Impl() {
    GEOSContext_setErrorMessageHandler_r(ctx, on_message, &error);
    GEOSContext_setNoticeMessageHandler_r(ctx, nullptr, nullptr);
  }
  ~Impl() { GEOS_finish_r(ctx); }

  [[noreturn]] void fail(const char* what) {
    throw std::runtime_error(std::string("GEOS ") + what + ": " +
                             (error.empty() ? "failed" : error));
  }

  // Owns a GEOS geometry.
  struct Geom {
    GEOSContextHandle_t ctx;
    GEOSGeometry* g;
    Geom(GEOSContextHandle_t c, GEOSGeometry* p) : ctx(c), g(p) {}
    Geom(const Geom&) = delete;
    Geom& operator=(Geom&& o) noexcept {
      std::swap(ctx, o.ctx);
      std::swap(g, o.g);
      return *this;
    }
    ~Geom() {
      if (g) GEOSGeom_destroy_r(ctx, g);
    }
  };

  GEOSGeometry* ring(const PlaneRing& r) {
    std::vector<double> xy;
    xy.reserve(2 * (r.size() + 1));
    for (const PlanePoint& p : r)
      xy.push_back(p.x), xy.push_back(p.y);
    xy.push_back(r.front().x), xy.push_back(r.front().y);
    GEOSCoordSequence* s =
        GEOSCoordSeq_copyFromBuffer_r(ctx, xy.data(), r.size() + 1, false, false);
    if (!s) fail("coordinates");
    GEOSGeometry* g = GEOSGeom_createLinearRing_r(ctx, s);
    if (!g) fail("ring");
    return g;
  }

  GEOSGeometry* polygon(const PlanePolygon& p) {
    GEOSGeometry* shell = ring(p.front());
    std::vector<GEOSGeometry*> holes;
    for (size_t i = 1; i < p.size(); ++i)
      holes.push_back(ring(p[i]));
    GEOSGeometry* g =
        GEOSGeom_createPolygon_r(ctx, shell, holes.data(), static_cast<unsigned>(holes.size()));
    if (!g) fail("polygon");
    return g;
  }

  Geom multi(const PlaneMultiPolygon& m) {
    std::vector<GEOSGeometry*> parts;
    for (const PlanePolygon& p : m)
      if (!p.empty() && p.front().size() >= 3) parts.push_back(polygon(p));
    GEOSGeometry* g = GEOSGeom_createCollection_r(ctx, GEOS_MULTIPOLYGON, parts.data(),
                                                  static_cast<unsigned>(parts.size()));
    if (!g) fail("multipolygon");
    return Geom(ctx, g);
  }

  PlaneRing read_ring(const GEOSGeometry* r) {
    const GEOSCoordSequence* s = GEOSGeom_getCoordSeq_r(ctx, r);
    unsigned n = 0;
    if (!s || !GEOSCoordSeq_getSize_r(ctx, s, &n)) fail("ring size");
    std::vector<double> xy(2 * size_t{n});
    if (n && !GEOSCoordSeq_copyToBuffer_r(ctx, s, xy.data(), false, false)) fail("ring read");
    PlaneRing out;
    for (unsigned i = 0; i + 1 < n; ++i)  // closed in GEOS, open here
      out.push_back({xy[2 * i], xy[2 * i + 1]});
    return out;
  }

  // Every polygon in `g` (a polygon, multipolygon or collection) into `out`.
  void read_polygons(const GEOSGeometry* g, PlaneMultiPolygon& out) {
    const int type = GEOSGeomTypeId_r(ctx, g);
    if (type == GEOS_POLYGON) {
      if (GEOSisEmpty_r(ctx, g)) return;
      PlanePolygon p;
      p.push_back(read_ring(GEOSGetExteriorRing_r(ctx, g)));
      const int holes = GEOSGetNumInteriorRings_r(ctx, g);
      for (int i = 0; i < holes; ++i)
        p.push_back(read_ring(GEOSGetInteriorRingN_r(ctx, g, i)));
      out.push_back(std::move(p));
    } else if (type == GEOS_MULTIPOLYGON || type == GEOS_GEOMETRYCOLLECTION) {
      const int n = GEOSGetNumGeometries_r(ctx, g);
      for (int i = 0; i < n; ++i)
        read_polygons(GEOSGetGeometryN_r(ctx, g, i), out);
    }  // points and lines (collapsed parts) are left out
  }
};

Geos::Geos() : impl_(std::make_unique<Impl>()) {}
Geos::~Geos() = default;

bool Geos::is_valid(const PlaneMultiPolygon& m) {
  const Impl::Geom g = impl_->multi(m);
  const char v = GEOSisValid_r(impl_->ctx, g.g);
  if (v == 2) impl_->fail("validity");
  return v == 1;
}

PlaneMultiPolygon Geos::make_valid(const PlaneMultiPolygon& m) {
  const Impl::Geom g = impl_->multi(m);
  GEOSMakeValidParams* params = GEOSMakeValidParams_create_r(impl_->ctx);
  GEOSMakeValidParams_setMethod_r(impl_->ctx, params, GEOS_MAKE_VALID_STRUCTURE);
  GEOSMakeValidParams_setKeepCollapsed_r(impl_->ctx, params, 0);
  const Impl::Geom v(impl_->ctx, GEOSMakeValidWithParams_r(impl_->ctx, g.g, params));
  GEOSMakeValidParams_destroy_r(impl_->ctx, params);
  if (!v.g) impl_->fail("MakeValid");
  PlaneMultiPolygon out;
  impl_->read_polygons(v.g, out);
  return out;
}

PlaneMultiPolygon Geos::clip(const PlaneMultiPolygon& m, double x0, double y0, double x1,
                             double y1) {
  const Impl::Geom g = impl_->multi(m);
  const Impl::Geom box(impl_->ctx, GEOSGeom_createRectangle_r(impl_->ctx, x0, y0, x1, y1));
  if (!box.g) impl_->fail("rectangle");
  const Impl::Geom c(impl_->ctx, GEOSIntersection_r(impl_->ctx, g.g, box.g));
  if (!c.g) impl_->fail("intersection");
  PlaneMultiPolygon out;
  impl_->read_polygons(c.g, out);
  return out;
}

std::vector<PlaneMultiPolygon> Geos::clip_to_boxes(const PlaneMultiPolygon& m,
                                                   const std::vector<Box>& boxes) {
  GEOSContextHandle_t ctx = impl_->ctx;
  const Impl::Geom g = impl_->multi(m);
  const GEOSPreparedGeometry* prepared = GEOSPrepare_r(ctx, g.g);
  if (!prepared) impl_->fail("prepare");
  // Whether (x, y) is inside `geom` (prepared: the input), by GEOS.
  auto contains = [&](const GEOSGeometry* geom, const GEOSPreparedGeometry* prep, double x,
                      double y) {
    const Impl::Geom pt(ctx, GEOSGeom_createPointFromXY_r(ctx, x, y));
    const char c = prep ? GEOSPreparedContains_r(ctx, prep, pt.g) : GEOSContains_r(ctx, geom, pt.g);
    if (c == 2) impl_->fail("contains");
    return c == 1;
  };
  std::vector<PlaneMultiPolygon> out(boxes.size());
  for (size_t i = 0; i < boxes.size(); ++i) {
    const Box& b = boxes[i];
    Impl::Geom c(ctx, GEOSClipByRect_r(ctx, g.g, b.x0, b.y0, b.x1, b.y1));
    if (!c.g) impl_->fail("rectangle clipping");
    // Rectangle clipping can turn a ring inside out (taking the box's
    // corners); where a corner's side disagrees with the input's, the
    // overlay intersection decides instead.
    bool trusted = true;
    for (const auto& [x, y] : {std::pair{b.x0, b.y0}, {b.x1, b.y0}, {b.x1, b.y1}, {b.x0, b.y1}})
      trusted = trusted && contains(c.g, nullptr, x, y) == contains(g.g, prepared, x, y);
    if (!trusted) {
      const Impl::Geom box(ctx, GEOSGeom_createRectangle_r(ctx, b.x0, b.y0, b.x1, b.y1));
      c = Impl::Geom(ctx, GEOSIntersection_r(ctx, g.g, box.g));
      if (!c.g) impl_->fail("intersection");
      ++overlay_fallbacks_;
    }
    impl_->read_polygons(c.g, out[i]);
  }
  GEOSPreparedGeom_destroy_r(ctx, prepared);
  return out;
}

PlanePoint Geos::inscribed_centre(const PlanePolygon& p, double tolerance) {
  const Impl::Geom g(impl_->ctx, impl_->polygon(p));
  const Impl::Geom line(impl_->ctx, GEOSMaximumInscribedCircle_r(impl_->ctx, g.g, tolerance));
  if (!line.g) impl_->fail("MaximumInscribedCircle");
  const GEOSCoordSequence* s = GEOSGeom_getCoordSeq_r(impl_->ctx, line.g);
  double x = 0, y = 0;
  if (!s || !GEOSCoordSeq_getXY_r(impl_->ctx, s, 0, &x, &y)) impl_->fail("MaximumInscribedCircle");
  return {x, y};
}

}  // namespace globe
