// Helpers of the line tests: writing synthetic GeoJSON inputs, reading
// extracted lines back through OGR, and a sampled Hausdorff distance.
#pragma once

#include <gdal.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "lines/line_geometry.hpp"

namespace globe_test {

using Polyline = std::vector<globe::XY>;

inline void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

// Lines of every feature id in a vector file's layer (all parts), optionally
// transformed to `to_crs`; `id_field` "" uses the 1-based feature order.
inline std::map<int64_t, std::vector<Polyline>> read_lines(const std::string& path,
                                                           const std::string& layer_name,
                                                           const std::string& id_field,
                                                           const std::string& to_crs = "",
                                                           const std::string& from_crs = "") {
  GDALAllRegister();
  std::map<int64_t, std::vector<Polyline>> out;
  GDALDatasetH ds = GDALOpenEx(path.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr);
  if (!ds) return out;
  OGRLayerH layer = layer_name.empty() ? GDALDatasetGetLayer(ds, 0)
                                       : GDALDatasetGetLayerByName(ds, layer_name.c_str());
  OGRCoordinateTransformationH ct = nullptr;
  if (!to_crs.empty() && layer) {
    OGRSpatialReferenceH dst = OSRNewSpatialReference(nullptr);
    OSRSetFromUserInput(dst, to_crs.c_str());
    OSRSetAxisMappingStrategy(dst, OAMS_TRADITIONAL_GIS_ORDER);
    OGRSpatialReferenceH src = nullptr;
    if (from_crs.empty()) {
      src = OSRClone(OGR_L_GetSpatialRef(layer));
    } else {
      src = OSRNewSpatialReference(nullptr);
      OSRSetFromUserInput(src, from_crs.c_str());
    }
    OSRSetAxisMappingStrategy(src, OAMS_TRADITIONAL_GIS_ORDER);
    ct = OCTNewCoordinateTransformation(src, dst);
    OSRRelease(src);
    OSRRelease(dst);
  }
  int64_t order = 0;
  for (OGRFeatureH f; layer && (f = OGR_L_GetNextFeature(layer));) {
    ++order;
    const int64_t id = id_field.empty()
                           ? order
                           : OGR_F_GetFieldAsInteger64(f, OGR_F_GetFieldIndex(f, id_field.c_str()));
    OGRGeometryH g = OGR_G_Clone(OGR_F_GetGeometryRef(f));
    if (g && ct) OGR_G_Transform(g, ct);
    std::vector<OGRGeometryH> stack{g};
    while (!stack.empty()) {
      OGRGeometryH h = stack.back();
      stack.pop_back();
      if (!h) continue;
      if (OGR_G_GetPointCount(h) > 0 && OGR_G_GetGeometryCount(h) == 0) {
        Polyline p;
        for (int i = 0; i < OGR_G_GetPointCount(h); ++i)
          p.push_back({OGR_G_GetX(h, i), OGR_G_GetY(h, i)});
        out[id].push_back(p);
      }
      for (int i = OGR_G_GetGeometryCount(h) - 1; i >= 0; --i)
        stack.push_back(OGR_G_GetGeometryRef(h, i));
    }
    OGR_G_DestroyGeometry(g);
    OGR_F_Destroy(f);
  }
  if (ct) OCTDestroyCoordinateTransformation(ct);
  GDALClose(ds);
  return out;
}

inline double distance_to_lines(globe::XY p, const std::vector<Polyline>& lines) {
  double best = INFINITY;
  for (const Polyline& l : lines)
    for (size_t i = 0; i + 1 < l.size(); ++i) {
      const double dx = l[i + 1].x - l[i].x, dy = l[i + 1].y - l[i].y;
      const double len2 = dx * dx + dy * dy;
      double t = len2 > 0 ? ((p.x - l[i].x) * dx + (p.y - l[i].y) * dy) / len2 : 0;
      t = std::clamp(t, 0.0, 1.0);
      best = std::min(best, std::hypot(p.x - l[i].x - t * dx, p.y - l[i].y - t * dy));
    }
  return best;
}

// Largest distance from points of `a` (vertices and 4 samples per segment)
// to the lines `b`: the directed Hausdorff distance, sampled.
inline double directed_hausdorff(const std::vector<Polyline>& a, const std::vector<Polyline>& b) {
  double worst = 0;
  for (const Polyline& l : a)
    for (size_t i = 0; i < l.size(); ++i)
      for (int k = 0; k < (i + 1 < l.size() ? 5 : 1); ++k) {
        const double t = k / 5.0;
        const globe::XY p{l[i].x + (i + 1 < l.size() ? t * (l[i + 1].x - l[i].x) : 0),
                          l[i].y + (i + 1 < l.size() ? t * (l[i + 1].y - l[i].y) : 0)};
        worst = std::max(worst, distance_to_lines(p, b));
      }
  return worst;
}

}  // namespace globe_test
