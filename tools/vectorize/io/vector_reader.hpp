// Reads features from OGR sources (the one place that walks OGR layers,
// features and geometries): selected layers, an attribute filter, the class
// field, numeric value fields, properties as JSON, and geometry flattened
// into line parts (lines, polygon rings, curves linearized) and points, in
// the layer's CRS. CSV files with coordinate columns are read as points.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geo/gdal_dataset.hpp"
#include "geo/spatial_ref.hpp"
#include "lines/line_geometry.hpp"

namespace globe {

struct VectorFeature {
  int layer = 0;                // index into VectorReader::layers()
  int64_t fid = 0;              // OGR's feature id (a CSV file's data row, from 1)
  std::string properties_json;  // {"field": value, ...}
  std::string class_value;      // the class field as text ("" without --class-field)
  std::vector<std::vector<XY>> lines;
  std::vector<XY> points;
  // With VectorReaderOptions::polygons: each polygon's rings (the exterior
  // first, then its holes; closed as OGR gives them), not in `lines`.
  std::vector<std::vector<std::vector<XY>>> polygons;
  std::vector<double> values;      // VectorReaderOptions::value_fields; NaN where null
  std::vector<std::string> texts;  // VectorReaderOptions::text_fields; "" where null
};

// What a layer declares it holds.
enum class LayerGeometry { kPoints, kLines, kPolygons, kOther };

struct VectorLayerInfo {
  std::string name;
  std::string source;  // file it comes from
  std::optional<SpatialRef> crs;
  int64_t feature_count = -1;  // -1 if unknown without a scan
  LayerGeometry geometry = LayerGeometry::kOther;
  std::vector<std::string> fields;  // attribute names
};

struct VectorReaderOptions {
  std::vector<std::string> layers;           // empty: every layer
  std::string where;                         // OGR SQL attribute filter
  std::string class_field;                   // "" for none
  std::optional<tileformat::Bounds> filter;  // lon/lat area (a fast pre-filter)
  std::string s_srs;                         // assigned CRS ("" keeps the files')
  bool properties = true;                    // false: properties_json stays empty
  bool polygons = false;                     // polygons into VectorFeature::polygons
  // Numeric fields read into VectorFeature::values; a missing or text field
  // is a UsageError naming the layer and its fields.
  std::vector<std::string> value_fields;
  // CSV files: the columns holding x and y (CRS: --s_srs, else lon/lat).
  std::optional<std::pair<std::string, std::string>> xy;
  std::string xy_option = "--xy";  // the option that gave `xy`, for messages
  // Fields read as text into VectorFeature::texts (any type); a missing one
  // is a UsageError naming the layer and its fields.
  std::vector<std::string> text_fields;
  // Whether every layer needs a CRS (an attribute table without geometry
  // does not: kNotNeeded).
  enum class Crs { kNeeded, kNotNeeded } crs = Crs::kNeeded;
  // The option that names each value or text field, for messages ("--fields
  // 'x': ..."); fields not listed say "field 'x'".
  std::map<std::string, std::string> field_options;
};

class VectorReader {
 public:
  // Opens every input and checks layers, filter fields, class field and CRS
  // up front, so bad input fails before anything is written. Throws
  // InputError / UsageError naming the file and layer.
  VectorReader(const std::vector<std::string>& inputs, const VectorReaderOptions& options);
  ~VectorReader();

  const std::vector<VectorLayerInfo>& layers() const { return layers_; }
  // Layers left out because they hold no geometry (e.g. the layer_styles
  // table QGIS adds to GeoPackages), as "FILE layer 'NAME'": for a note.
  // Only where geometry is needed (Crs::kNeeded) and no --layer named them.
  const std::vector<std::string>& skipped_tables() const { return skipped_; }
  // Next feature of the current layer, then of the next layers, in file
  // order. False at the end.
  bool next(VectorFeature& out);

 private:
  struct LayerHandle;
  std::vector<GdalDataset> datasets_;
  std::vector<VectorLayerInfo> layers_;
  std::vector<std::string> skipped_;
  std::vector<std::unique_ptr<LayerHandle>> handles_;
  size_t current_ = 0;
  bool properties_ = true;
  bool polygons_ = false;
};

}  // namespace globe
