// Writes decoded lines and points as vector data through OGR (the one place
// that creates OGR layers and features), in the tiling CRS: layers "lines"
// and "points" (of line packages) and "polygons" (of area packages) with
// fields feature_id, class, layer, tile and properties; layer "places" (of point packages) with
// fields place_id, places, tile, properties and one real field per value. Built under a temporary
// name and renamed by commit().
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "geo/gdal_dataset.hpp"
#include "lines/line_geometry.hpp"
#include "tileformat/package.hpp"

namespace globe {

struct VectorAttributes {
  int64_t feature_id = 0;
  std::string class_name, layer, tile, properties;
};

struct PlaceAttributes {
  int64_t place_id = 0;
  int64_t places = 1;  // source places it stands for
  std::string tile, properties;
  std::vector<double> values;  // one per value field
};

class VectorWriter {
 public:
  // Throws OutputError if `path` exists and kFail, or cannot be created.
  VectorWriter(std::string path, tileformat::IfExists if_exists, const std::string& crs_wkt);
  ~VectorWriter();  // deletes the temporary file unless committed
  VectorWriter(const VectorWriter&) = delete;
  VectorWriter& operator=(const VectorWriter&) = delete;

  void add_line(const std::vector<XY>& points, const VectorAttributes& a);
  void add_point(XY p, const VectorAttributes& a);
  // A polygon: its exterior ring, then its holes (open rings).
  void add_polygon(const std::vector<std::vector<XY>>& rings, const VectorAttributes& a);
  // The value fields of the "places" layer (before the first add_place).
  void set_value_fields(std::vector<std::string> names) { value_fields_ = std::move(names); }
  void add_place(XY p, const PlaceAttributes& a);
  void commit();
  uint64_t lines() const { return lines_; }
  uint64_t points() const { return points_; }
  uint64_t polygons() const { return polygons_; }

 private:
  enum class Kind { kLines, kPoints, kPlaces, kPolygons };  // one layer each
  void* layer(Kind kind);                                   // OGRLayerH
  // Writes one feature of `geometry` (taken over) to the layer of `kind`;
  // set_fields(OGRFeatureH) fills its fields.
  void add(void* geometry, Kind kind, const std::function<void(void*)>& set_fields);
  void add(void* geometry, Kind kind, const VectorAttributes& a);
  std::string path_, temp_, crs_wkt_;
  GdalDataset ds_;
  void* lines_layer_ = nullptr;
  void* points_layer_ = nullptr;
  void* places_layer_ = nullptr;
  void* polygons_layer_ = nullptr;
  std::vector<std::string> value_fields_;
  uint64_t lines_ = 0, points_ = 0, polygons_ = 0;
  bool committed_ = false, in_transaction_ = false;
};

}  // namespace globe
