// Label candidates the vector tools store (docs/labels.md "What the tools
// store"): which attribute names a feature (--label-field FIELD|auto), its
// priority (--priority-field, else a size), the frame-to-longitude/latitude
// conversion of anchors, an area's anchor (the pole of inaccessibility of its
// largest part) and a line's path. The table itself is tileformat's
// LabelTableWriter; nothing here touches OGR or GEOS directly.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "geo/geos_polygons.hpp"
#include "geo/spatial_ref.hpp"
#include "io/vector_reader.hpp"
#include "kit/progress.hpp"
#include "lines/line_projector.hpp"

namespace globe {

// --label-field and --priority-field as given.
struct LabelOptions {
  std::string field;     // "" none, "auto", or an attribute name
  std::string priority;  // "" none (a size decides), or a numeric attribute
  bool enabled() const { return !field.empty(); }
};

// The attribute that names features: `option` itself, or for "auto" the
// first of name, NAME, Name, name_en, NAME_EN, name_long, NAME_LONG,
// NAMELSAD, nom, NOM, city, CITY, label, LABEL that the first layer has ("" when none:
// no labels). Throws UsageError naming the layer's fields when an explicit
// field or the priority field is missing from a layer.
std::string resolve_label_field(const LabelOptions& o, const std::vector<VectorLayerInfo>& layers);

// Resolves the label field (for `auto`, opening the inputs once for their
// fields; an explicit one the caller's reader checks) and
// asks `ro` for it and the priority field; returns the field ("" for no
// labels, with a note when auto found none). *priority_index: the priority
// field's index in VectorFeature::values (-1 for none).
std::string request_label_fields(const LabelOptions& o, const std::vector<std::string>& inputs,
                                 VectorReaderOptions& ro, Progress& progress, int* priority_index);

// Longitude/latitude (degrees, -180..180) of a point of a vector frame.
class FrameLonLat {
 public:
  // `target`: the tiling CRS of a projected frame (nullptr for the global ones).
  FrameLonLat(TargetFrame frame, const SpatialRef* target);
  ~FrameLonLat();
  // False where PROJ cannot transform the point.
  bool operator()(XY frame_point, XY& lonlat) const;

 private:
  TargetFrame frame_;
  std::unique_ptr<CoordTransform> to_lonlat_;
};

// An area's label anchor: the centre of the largest circle inside its
// largest part (GEOS MaximumInscribedCircle, to 1/200 of the part's size)
// and the feature's whole area (frame units squared: the default priority).
struct AreaAnchor {
  PlanePoint at;
  double area = 0;
};
AreaAnchor area_anchor(const PlaneMultiPolygon& polygons, Geos& geos);

// A line's label path: its longest part, thinned (Douglas-Peucker at 1/500
// of its length, at most 256 points) and then cut into segments of at most
// 1/32 of its length (straight in the frame, as the line is drawn), and the
// feature's length in frame units.
struct LinePath {
  std::vector<XY> points;  // frame
  double length = 0;       // of the whole feature, frame units
};
LinePath line_label_path(const std::vector<std::vector<XY>>& parts);

// The package's "globe:labels" metadata: {"field", "priority", "count"}.
std::string labels_metadata_json(const std::string& field, const std::string& priority,
                                 int64_t count);

}  // namespace globe
