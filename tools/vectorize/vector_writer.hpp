// Writes decoded lines and points as vector data through OGR (the one place
// that creates OGR layers and features): layers "lines" and "points" with
// fields feature_id, class, layer, tile and properties, in the tiling CRS.
// Built under a temporary name and renamed by commit().
#pragma once

#include <string>
#include <vector>

#include "gdal_dataset.hpp"
#include "line_geometry.hpp"
#include "tileformat/package.hpp"

namespace globe {

struct VectorAttributes {
  int64_t feature_id = 0;
  std::string class_name, layer, tile, properties;
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
  void commit();
  uint64_t lines() const { return lines_; }
  uint64_t points() const { return points_; }

 private:
  enum class Kind { kLines, kPoints };  // one layer each
  void* layer(Kind kind);               // OGRLayerH
  void add(void* geometry, Kind kind, const VectorAttributes& a);
  std::string path_, temp_, crs_wkt_;
  GdalDataset ds_;
  void* lines_layer_ = nullptr;
  void* points_layer_ = nullptr;
  uint64_t lines_ = 0, points_ = 0;
  bool committed_ = false, in_transaction_ = false;
};

}  // namespace globe
