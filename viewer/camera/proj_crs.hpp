// The viewer's one wrapper around the PROJ C API (the viewer links no GDAL,
// docs/architecture.md): CRS texts as packages store them (WKT, or
// "EPSG:n") are compared and transformed with every result checked. Axis
// order is always x/east first (longitude before latitude).
#pragma once

#include <memory>
#include <string>

namespace globe::viewer {

class ProjTransform {
 public:
  // Throws InputError naming `context` if PROJ cannot read either CRS or
  // find a transformation between them.
  ProjTransform(const std::string& from_crs, const std::string& to_crs, const std::string& context);
  ~ProjTransform();
  ProjTransform(const ProjTransform&) = delete;
  ProjTransform& operator=(const ProjTransform&) = delete;

  // Transforms one point in place; false where PROJ cannot (outside the
  // projection's domain). Not thread-safe (one PROJ context per object).
  bool transform(double& x, double& y) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Whether the CRS is geographic (degrees); throws InputError naming `context`.
bool crs_is_geographic(const std::string& crs, const std::string& context);
// Whether two CRS are the same but for a geographic CRS's axis order; an
// unreadable one throws InputError naming its context.
bool crs_equivalent(const std::string& a, const std::string& a_context, const std::string& b,
                    const std::string& b_context);

}  // namespace globe::viewer
