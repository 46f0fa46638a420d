// Polygons burnt into masks (see polygon_mask.hpp).
#include "geo/polygon_mask.hpp"

#include <gdal_alg.h>
#include <ogr_api.h>

#include <algorithm>

#include "geo/gdal_dataset.hpp"
#include "geo/spatial_ref.hpp"
#include "runtime/errors.hpp"

namespace globe {

struct PolygonMask::Impl {
  std::vector<OGRGeometryH> geometries;  // lon/lat, owned
  std::vector<OGREnvelope> envelopes;
  ~Impl() {
    for (OGRGeometryH g : geometries)
      OGR_G_DestroyGeometry(g);
  }
};

PolygonMask::PolygonMask(const std::string& path) : impl_(std::make_unique<Impl>()) {
  gdal_init();
  GdalDataset ds = GdalDataset::open_vector(path);
  const SpatialRef lonlat = SpatialRef::from_user_input("EPSG:4326", "water mask");
  for (int l = 0; l < GDALDatasetGetLayerCount(ds.get()); ++l) {
    OGRLayerH layer = GDALDatasetGetLayer(ds.get(), l);
    const OGRwkbGeometryType type = wkbFlatten(OGR_L_GetGeomType(layer));
    if (type != wkbPolygon && type != wkbMultiPolygon && type != wkbUnknown) continue;
    OGRSpatialReferenceH srs = OGR_L_GetSpatialRef(layer);
    if (!srs)
      throw InputError(path + ": layer " + OGR_L_GetName(layer) +
                       " has no CRS; give the water polygons a .prj or use a GeoPackage");
    OGRSpatialReferenceH source = OSRClone(srs);
    OSRSetAxisMappingStrategy(source, OAMS_TRADITIONAL_GIS_ORDER);
    OGRCoordinateTransformationH to_lonlat = OCTNewCoordinateTransformation(source, lonlat.get());
    OSRRelease(source);
    if (!to_lonlat)
      throw InputError(path + ": no transformation from layer " + OGR_L_GetName(layer) +
                       "'s CRS to longitude/latitude");
    OGR_L_ResetReading(layer);
    while (OGRFeatureH f = OGR_L_GetNextFeature(layer)) {
      OGRGeometryH g = OGR_F_GetGeometryRef(f);
      const OGRwkbGeometryType gt = g ? wkbFlatten(OGR_G_GetGeometryType(g)) : wkbUnknown;
      if (gt == wkbPolygon || gt == wkbMultiPolygon) {
        OGRGeometryH copy = OGR_G_Clone(g);
        if (OGR_G_Transform(copy, to_lonlat) == OGRERR_NONE) {
          OGREnvelope env;
          OGR_G_GetEnvelope(copy, &env);
          impl_->geometries.push_back(copy);
          impl_->envelopes.push_back(env);
        } else {
          OGR_G_DestroyGeometry(copy);
        }
      }
      OGR_F_Destroy(f);
    }
    OCTDestroyCoordinateTransformation(to_lonlat);
  }
  if (impl_->geometries.empty()) throw InputError(path + ": no polygons to make a water mask of");
}

PolygonMask::~PolygonMask() = default;

size_t PolygonMask::polygons() const {
  return impl_->geometries.size();
}

std::vector<uint8_t> PolygonMask::rasterize(double west, double south, double east, double north,
                                            int size) {
  std::vector<uint8_t> out(size_t(size) * size, 0);
  std::vector<OGRGeometryH> near;
  for (size_t k = 0; k < impl_->geometries.size(); ++k) {
    const OGREnvelope& e = impl_->envelopes[k];
    if (e.MaxX >= west && e.MinX <= east && e.MaxY >= south && e.MinY <= north)
      near.push_back(impl_->geometries[k]);
  }
  if (near.empty()) return out;
  std::lock_guard lock(mutex_);  // the geometries are shared
  GdalDataset mem = GdalDataset::create_raster("MEM", "", size, size, 1, GDT_Byte);
  double gt[6] = {west, (east - west) / size, 0, north, 0, -(north - south) / size};
  GDALSetGeoTransform(mem.get(), gt);
  int band = 1;
  double burn = 255;
  gdal_check(GDALRasterizeGeometries(mem.get(), 1, &band, int(near.size()), near.data(), nullptr,
                                     nullptr, &burn, nullptr, nullptr, nullptr),
             "rasterizing the water polygons");
  gdal_check(
      GDALRasterIO(mem.band(1), GF_Read, 0, 0, size, size, out.data(), size, size, GDT_Byte, 0, 0),
      "reading the water mask");
  return out;
}

}  // namespace globe
