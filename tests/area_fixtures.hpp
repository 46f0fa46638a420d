// What the tests of area packages share: North Carolina's counties
// (samples/data/nc.gpkg) read with OGR, each with a point well inside it, the
// reference the area tests check fills and tiles against.
#pragma once

#include <string>
#include <vector>

#include <gdal.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include "test_support.hpp"

namespace globe_test {

// A county of samples/data/nc.gpkg: its name, BIR74, and the point inside it
// farthest from its border among a 24 x 24 grid over its envelope (lon/lat,
// WGS 84), with that distance in degrees.
struct County {
  std::string name;
  double births = 0, lon = 0, lat = 0, clearance = 0;
};

inline std::vector<County> nc_counties() {
  GDALAllRegister();
  std::vector<County> out;
  GDALDatasetH ds =
      GDALOpenEx((samples() / "nc.gpkg").c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr);
  if (!ds) {
    ADD_FAILURE() << "OGR cannot open nc.gpkg";
    return out;
  }
  OGRLayerH layer = GDALDatasetGetLayer(ds, 0);
  OGRSpatialReferenceH from = OSRClone(OGR_L_GetSpatialRef(layer));
  OGRSpatialReferenceH to = OSRNewSpatialReference(nullptr);
  OSRImportFromEPSG(to, 4326);
  OSRSetAxisMappingStrategy(from, OAMS_TRADITIONAL_GIS_ORDER);
  OSRSetAxisMappingStrategy(to, OAMS_TRADITIONAL_GIS_ORDER);
  OGRCoordinateTransformationH ct = OCTNewCoordinateTransformation(from, to);
  OGR_L_ResetReading(layer);
  while (OGRFeatureH f = OGR_L_GetNextFeature(layer)) {
    County c;
    c.name = OGR_F_GetFieldAsString(f, OGR_F_GetFieldIndex(f, "NAME"));
    c.births = OGR_F_GetFieldAsDouble(f, OGR_F_GetFieldIndex(f, "BIR74"));
    OGRGeometryH g = OGR_G_Clone(OGR_F_GetGeometryRef(f));
    OGR_G_Transform(g, ct);
    OGRGeometryH border = OGR_G_Boundary(g);
    OGREnvelope e;
    OGR_G_GetEnvelope(g, &e);
    for (int i = 0; i < 24; ++i)
      for (int j = 0; j < 24; ++j) {
        OGRGeometryH p = OGR_G_CreateGeometry(wkbPoint);
        const double lon = e.MinX + (i + 0.5) / 24 * (e.MaxX - e.MinX),
                     lat = e.MinY + (j + 0.5) / 24 * (e.MaxY - e.MinY);
        OGR_G_SetPoint_2D(p, 0, lon, lat);
        if (OGR_G_Contains(g, p)) {
          const double d = OGR_G_Distance(p, border);
          if (d > c.clearance) c.clearance = d, c.lon = lon, c.lat = lat;
        }
        OGR_G_DestroyGeometry(p);
      }
    OGR_G_DestroyGeometry(border);
    OGR_G_DestroyGeometry(g);
    OGR_F_Destroy(f);
    out.push_back(c);
  }
  OCTDestroyCoordinateTransformation(ct);
  OSRDestroySpatialReference(from);
  OSRDestroySpatialReference(to);
  GDALClose(ds);
  return out;
}

}  // namespace globe_test
