// Helpers of the point tests: writing CSV inputs and reading the places of
// an `extract` back through OGR (GDAL's own reader, not the package
// library), in longitude/latitude.
#pragma once

#include <gdal.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace globe_test {

struct CsvPlace {
  std::string name;
  double lon = 0, lat = 0;
  std::vector<double> values;
};

// name,lon,lat,v0,v1,... with the given value column names.
inline void write_places_csv(const std::string& path, const std::vector<std::string>& fields,
                             const std::vector<CsvPlace>& places) {
  std::ofstream out(path);
  out.precision(17);
  out << "name,lon,lat";
  for (const std::string& f : fields)
    out << "," << f;
  out << "\n";
  for (const CsvPlace& p : places) {
    out << p.name << "," << p.lon << "," << p.lat;
    for (double v : p.values)
      out << "," << v;
    out << "\n";
  }
}

struct ExtractedPlace {
  int64_t id = 0, places = 0;
  double x = 0, y = 0;  // the extract's CRS (the tiling's)
  double lon = 0, lat = 0;
  std::string tile, properties;
  std::vector<double> values;  // in the order of `fields`
};

// The "places" layer of an extract, positions in lon/lat.
inline std::vector<ExtractedPlace> read_places(const std::string& path,
                                               const std::vector<std::string>& fields) {
  GDALAllRegister();
  std::vector<ExtractedPlace> out;
  GDALDatasetH ds = GDALOpenEx(path.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr);
  if (!ds) return out;
  OGRLayerH layer = GDALDatasetGetLayerByName(ds, "places");
  OGRCoordinateTransformationH ct = nullptr;
  if (layer) {
    OGRSpatialReferenceH src = OSRClone(OGR_L_GetSpatialRef(layer));
    OGRSpatialReferenceH dst = OSRNewSpatialReference(nullptr);
    OSRSetFromUserInput(dst, "EPSG:4326");
    OSRSetAxisMappingStrategy(src, OAMS_TRADITIONAL_GIS_ORDER);
    OSRSetAxisMappingStrategy(dst, OAMS_TRADITIONAL_GIS_ORDER);
    ct = OCTNewCoordinateTransformation(src, dst);
    OSRRelease(src);
    OSRRelease(dst);
  }
  for (OGRFeatureH f; layer && (f = OGR_L_GetNextFeature(layer));) {
    ExtractedPlace p;
    p.id = OGR_F_GetFieldAsInteger64(f, OGR_F_GetFieldIndex(f, "place_id"));
    p.places = OGR_F_GetFieldAsInteger64(f, OGR_F_GetFieldIndex(f, "places"));
    p.tile = OGR_F_GetFieldAsString(f, OGR_F_GetFieldIndex(f, "tile"));
    p.properties = OGR_F_GetFieldAsString(f, OGR_F_GetFieldIndex(f, "properties"));
    for (const std::string& name : fields)
      p.values.push_back(OGR_F_GetFieldAsDouble(f, OGR_F_GetFieldIndex(f, name.c_str())));
    OGRGeometryH g = OGR_F_GetGeometryRef(f);
    double x = OGR_G_GetX(g, 0), y = OGR_G_GetY(g, 0), z = 0;
    p.x = x;
    p.y = y;
    if (ct) OCTTransform(ct, 1, &x, &y, &z);
    p.lon = x;
    p.lat = y;
    out.push_back(std::move(p));
    OGR_F_Destroy(f);
  }
  if (ct) OCTDestroyCoordinateTransformation(ct);
  GDALClose(ds);
  return out;
}

}  // namespace globe_test
