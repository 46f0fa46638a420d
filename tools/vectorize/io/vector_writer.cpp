// OGR vector output (see vector_writer.hpp).
#include "io/vector_writer.hpp"

#include <ogr_api.h>
#include <ogr_srs_api.h>

#include <filesystem>

#include "geo/spatial_ref.hpp"
#include "runtime/errors.hpp"

namespace globe {

VectorWriter::VectorWriter(std::string path, tileformat::IfExists if_exists,
                           const std::string& crs_wkt)
    : path_(std::move(path)), crs_wkt_(crs_wkt) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(path_, ec) && if_exists == tileformat::IfExists::kFail)
    throw OutputError(path_ + ": output exists; pass --force to replace it");
  const fs::path p(path_);
  temp_ = (p.parent_path() / (p.stem().string() + ".tmp" + p.extension().string())).string();
  fs::remove(temp_, ec);
  gdal_init();
  ds_ = GdalDataset::create_vector(temp_);
  in_transaction_ = GDALDatasetStartTransaction(ds_.get(), FALSE) == OGRERR_NONE;
}

VectorWriter::~VectorWriter() {
  if (committed_) return;
  ds_ = GdalDataset();
  std::error_code ec;
  std::filesystem::remove(temp_, ec);
}

void* VectorWriter::layer(Kind kind) {
  void*& l = kind == Kind::kPoints     ? points_layer_
             : kind == Kind::kPlaces   ? places_layer_
             : kind == Kind::kPolygons ? polygons_layer_
                                       : lines_layer_;
  if (l) return l;
  const SpatialRef srs = SpatialRef::from_wkt(crs_wkt_, path_ + " (the package's CRS)");
  const char* name = kind == Kind::kPoints     ? "points"
                     : kind == Kind::kPlaces   ? "places"
                     : kind == Kind::kPolygons ? "polygons"
                                               : "lines";
  const OGRwkbGeometryType type = kind == Kind::kLines      ? wkbLineString
                                  : kind == Kind::kPolygons ? wkbPolygon
                                                            : wkbPoint;
  OGRLayerH layer = GDALDatasetCreateLayer(ds_.get(), name, srs.get(), type, nullptr);
  if (!layer) throw OutputError(temp_ + ": cannot create a layer (" + gdal_last_error() + ")");
  std::vector<std::pair<std::string, OGRFieldType>> fields;
  if (kind == Kind::kPlaces) {
    fields = {{"place_id", OFTInteger64},
              {"places", OFTInteger64},
              {"tile", OFTString},
              {"properties", OFTString}};
    for (const std::string& v : value_fields_)
      fields.emplace_back(v, OFTReal);
  } else {
    fields = {{"feature_id", OFTInteger64},
              {"class", OFTString},
              {"layer", OFTString},
              {"tile", OFTString},
              {"properties", OFTString}};
  }
  for (const auto& [field, type] : fields) {
    OGRFieldDefnH fd = OGR_Fld_Create(field.c_str(), type);
    const OGRErr err = OGR_L_CreateField(layer, fd, TRUE);
    OGR_Fld_Destroy(fd);
    if (err != OGRERR_NONE)
      throw OutputError(temp_ + ": cannot create field " + field + " (" + gdal_last_error() + ")");
  }
  l = layer;
  return l;
}

void VectorWriter::add(void* geometry, Kind kind, const VectorAttributes& a) {
  add(geometry, kind, [&](void* feature) {
    OGRFeatureH f = static_cast<OGRFeatureH>(feature);
    OGR_F_SetFieldInteger64(f, 0, a.feature_id);
    OGR_F_SetFieldString(f, 1, a.class_name.c_str());
    OGR_F_SetFieldString(f, 2, a.layer.c_str());
    OGR_F_SetFieldString(f, 3, a.tile.c_str());
    OGR_F_SetFieldString(f, 4, a.properties.c_str());
  });
}

void VectorWriter::add(void* geometry, Kind kind, const std::function<void(void*)>& set_fields) {
  OGRLayerH l = static_cast<OGRLayerH>(layer(kind));
  OGRFeatureH f = OGR_F_Create(OGR_L_GetLayerDefn(l));
  if (!f) {
    OGR_G_DestroyGeometry(static_cast<OGRGeometryH>(geometry));
    throw OutputError(temp_ + ": cannot create a feature (out of memory?)");
  }
  set_fields(f);
  OGRErr err = OGR_F_SetGeometryDirectly(f, static_cast<OGRGeometryH>(geometry));
  if (err == OGRERR_NONE) err = OGR_L_CreateFeature(l, f);
  OGR_F_Destroy(f);
  if (err != OGRERR_NONE)
    throw OutputError(temp_ + ": cannot write a feature (" + gdal_last_error() +
                      "); check free space");
}

void VectorWriter::add_line(const std::vector<XY>& pts, const VectorAttributes& a) {
  OGRGeometryH g = OGR_G_CreateGeometry(wkbLineString);
  for (const XY& p : pts)
    OGR_G_AddPoint_2D(g, p.x, p.y);
  add(g, Kind::kLines, a);
  ++lines_;
}

void VectorWriter::add_point(XY p, const VectorAttributes& a) {
  OGRGeometryH g = OGR_G_CreateGeometry(wkbPoint);
  OGR_G_SetPoint_2D(g, 0, p.x, p.y);
  add(g, Kind::kPoints, a);
  ++points_;
}

void VectorWriter::add_polygon(const std::vector<std::vector<XY>>& rings,
                               const VectorAttributes& a) {
  OGRGeometryH g = OGR_G_CreateGeometry(wkbPolygon);
  for (const std::vector<XY>& r : rings) {
    OGRGeometryH ring = OGR_G_CreateGeometry(wkbLinearRing);
    for (const XY& p : r)
      OGR_G_AddPoint_2D(ring, p.x, p.y);
    if (!r.empty()) OGR_G_AddPoint_2D(ring, r.front().x, r.front().y);
    OGR_G_AddGeometryDirectly(g, ring);
  }
  add(g, Kind::kPolygons, a);
  ++polygons_;
}

void VectorWriter::add_place(XY p, const PlaceAttributes& a) {
  OGRGeometryH g = OGR_G_CreateGeometry(wkbPoint);
  OGR_G_SetPoint_2D(g, 0, p.x, p.y);
  add(g, Kind::kPlaces, [&](void* feature) {
    OGRFeatureH f = static_cast<OGRFeatureH>(feature);
    OGR_F_SetFieldInteger64(f, 0, a.place_id);
    OGR_F_SetFieldInteger64(f, 1, a.places);
    OGR_F_SetFieldString(f, 2, a.tile.c_str());
    OGR_F_SetFieldString(f, 3, a.properties.c_str());
    for (size_t i = 0; i < a.values.size() && i < value_fields_.size(); ++i)
      OGR_F_SetFieldDouble(f, static_cast<int>(4 + i), a.values[i]);
  });
  ++points_;
}

void VectorWriter::commit() {
  if (in_transaction_ && GDALDatasetCommitTransaction(ds_.get()) != OGRERR_NONE)
    throw OutputError(temp_ + ": cannot commit (" + gdal_last_error() + "); check free space");
  ds_ = GdalDataset();  // closes and flushes
  std::error_code ec;
  std::filesystem::rename(temp_, path_, ec);
  if (ec) throw OutputError(path_ + ": cannot rename the finished file (" + ec.message() + ")");
  committed_ = true;
}

}  // namespace globe
