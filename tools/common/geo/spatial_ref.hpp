// The one wrapper around OGR spatial references and PROJ coordinate
// transformations (through GDAL's OSR/OCT API). Axis order is always
// "traditional GIS": x = easting/longitude, y = northing/latitude.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <ogr_srs_api.h>

#include "tileformat/tiling.hpp"

namespace globe {

class SpatialRef {
 public:
  // From "EPSG:4326", a PROJ string or WKT; throws UsageError with `context`.
  static SpatialRef from_user_input(const std::string& text, const std::string& context);
  static SpatialRef from_wkt(const std::string& wkt, const std::string& context);

  OGRSpatialReferenceH get() const { return h_.get(); }
  std::string wkt2() const;
  bool is_geographic() const { return OSRIsGeographic(h_.get()) != 0; }
  bool is_same(const SpatialRef& o) const { return OSRIsSame(h_.get(), o.get()) != 0; }
  std::string name() const;
  // Metres per unit of a projected CRS's axes (1 for metres).
  double linear_units() const { return OSRGetLinearUnits(h_.get(), nullptr); }

 private:
  void reset(OGRSpatialReferenceH h) {
    h_ = std::shared_ptr<std::remove_pointer_t<OGRSpatialReferenceH>>(
        h, [](OGRSpatialReferenceH p) { OSRRelease(p); });
  }
  std::shared_ptr<std::remove_pointer_t<OGRSpatialReferenceH>> h_;  // immutable after construction
};

class CoordTransform {
 public:
  // Throws InputError naming both CRSs if PROJ has no transformation.
  CoordTransform(const SpatialRef& from, const SpatialRef& to);
  ~CoordTransform();
  CoordTransform(const CoordTransform&) = delete;
  CoordTransform& operator=(const CoordTransform&) = delete;

  // Transforms points in place; returns false for any point that failed.
  bool transform(std::vector<double>& x, std::vector<double>& y) const;
  // The same, with each point's success in `ok` (1 = transformed).
  void transform(std::vector<double>& x, std::vector<double>& y, std::vector<int>& ok) const;
  // Bounds of a densified rectangle; nullopt-like empty bounds on failure.
  bool transform_bounds(const tileformat::Bounds& in, tileformat::Bounds& out) const;

 private:
  OGRCoordinateTransformationH h_ = nullptr;
};

}  // namespace globe
