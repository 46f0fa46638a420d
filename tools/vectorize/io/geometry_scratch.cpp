// Projected-feature scratch records (see geometry_scratch.hpp).
#include "io/geometry_scratch.hpp"

#include "tileformat/byte_io.hpp"

namespace globe {

void GeometryScratch::write(const ProjectedFeature& f) {
  tileformat::ByteWriter w;
  w.u64(f.id);
  w.u32(f.class_id);
  w.u32(f.zooms);
  w.u32(static_cast<uint32_t>(f.lines.size()));
  w.u32(static_cast<uint32_t>(f.points.size()));
  auto put_xy = [&](const XY& p) {
    w.f64(p.x);
    w.f64(p.y);
  };
  for (const auto& part : f.lines) {
    w.u32(static_cast<uint32_t>(part.size()));
    for (const XY& p : part)
      put_xy(p);
  }
  for (const XY& p : f.points)
    put_xy(p);
  file_.append(w.take());
}

bool GeometryScratch::read(ProjectedFeature& f) {
  if (!file_.next(buffer_)) return false;
  tileformat::ByteReader r(buffer_, file_.path() + ": scratch feature", "scratch");
  f.id = r.u64();
  f.class_id = r.u32();
  f.zooms = r.u32();
  f.lines.resize(r.u32());
  f.points.resize(r.u32());
  auto get_xy = [&](XY& p) {
    p.x = r.f64();
    p.y = r.f64();
  };
  for (auto& part : f.lines) {
    part.resize(r.u32());
    for (XY& p : part)
      get_xy(p);
  }
  for (XY& p : f.points)
    get_xy(p);
  r.expect_end();
  return true;
}

}  // namespace globe
