// Label candidates (see label_candidates.hpp).
#include "labels/label_candidates.hpp"

#include <algorithm>
#include <cmath>

#include "areas/area_geometry.hpp"
#include "runtime/errors.hpp"
#include "tileformat/json.hpp"

namespace globe {
namespace {

const char* const kNameFields[] = {"name",      "NAME",      "Name",     "name_en", "NAME_EN",
                                   "name_long", "NAME_LONG", "NAMELSAD", "nom",     "NOM",
                                   "city",      "CITY",      "label",    "LABEL"};

bool has_field(const VectorLayerInfo& l, const std::string& f) {
  return std::find(l.fields.begin(), l.fields.end(), f) != l.fields.end();
}

void require_field(const VectorLayerInfo& l, const std::string& f, const char* option) {
  if (has_field(l, f)) return;
  std::string names;
  for (const std::string& n : l.fields)
    names += (names.empty() ? "" : ", ") + n;
  throw UsageError(std::string(option) + " '" + f + "': " + l.source + " layer '" + l.name +
                   "' has no such field; its fields are: " + (names.empty() ? "(none)" : names));
}

double polygon_area(const PlanePolygon& p) {
  double a = 0;
  for (size_t i = 0; i < p.size(); ++i)
    a += (i == 0 ? 1 : -1) * std::abs(ring_area2(p[i])) / 2;
  return std::max(a, 0.0);
}

}  // namespace

std::string resolve_label_field(const LabelOptions& o, const std::vector<VectorLayerInfo>& layers) {
  if (!o.enabled() || layers.empty()) return "";
  std::string field = o.field;
  if (field == "auto") {
    field.clear();
    for (const char* f : kNameFields)
      if (has_field(layers.front(), f)) {
        field = f;
        break;
      }
    if (field.empty()) return "";
  }
  for (const VectorLayerInfo& l : layers) {
    require_field(l, field, "--label-field");
    if (!o.priority.empty()) require_field(l, o.priority, "--priority-field");
  }
  return field;
}

std::string request_label_fields(const LabelOptions& o, const std::vector<std::string>& inputs,
                                 VectorReaderOptions& ro, Progress& progress, int* priority_index) {
  if (priority_index) *priority_index = -1;
  if (!o.enabled()) return "";
  // Only `auto` needs the layers' fields before the reader opens; an
  // explicit field is checked by the reader itself (a UsageError naming the
  // layer's fields), so the inputs are not opened twice for it.
  const std::string field =
      o.field == "auto" ? resolve_label_field(o, VectorReader(inputs, ro).layers()) : o.field;
  if (field.empty()) {
    progress.note("--label-field auto: no name field (name, NAME, ...) in " + inputs.front() +
                  "; no labels");
    return "";
  }
  ro.text_fields.push_back(field);
  ro.field_options[field] = "--label-field";
  if (!o.priority.empty()) {
    if (priority_index) *priority_index = static_cast<int>(ro.value_fields.size());
    ro.value_fields.push_back(o.priority);
    ro.field_options[o.priority] = "--priority-field";
  }
  return field;
}

FrameLonLat::FrameLonLat(TargetFrame frame, const SpatialRef* target) : frame_(frame) {
  if (frame == TargetFrame::kProjected && target)
    to_lonlat_ = std::make_unique<CoordTransform>(
        *target, SpatialRef::from_user_input("OGC:CRS84", "label anchors"));
}

FrameLonLat::~FrameLonLat() = default;

bool FrameLonLat::operator()(XY p, XY& out) const {
  if (frame_ != TargetFrame::kProjected) {
    out = LineProjector::frame_to_lonlat(frame_, p);
  } else {
    if (!to_lonlat_) return false;
    std::vector<double> x{p.x}, y{p.y};
    if (!to_lonlat_->transform(x, y) || !std::isfinite(x[0]) || !std::isfinite(y[0])) return false;
    out = {x[0], y[0]};
  }
  out.x = std::remainder(out.x, 360.0);  // -180..180
  return std::abs(out.y) <= 90;
}

AreaAnchor area_anchor(const PlaneMultiPolygon& polygons, Geos& geos) {
  AreaAnchor a;
  const PlanePolygon* largest = nullptr;
  double largest_area = -1;
  for (const PlanePolygon& p : polygons) {
    const double area = polygon_area(p);
    a.area += area;
    if (area > largest_area) largest_area = area, largest = &p;
  }
  if (!largest || largest->empty()) return a;
  double x0 = HUGE_VAL, y0 = HUGE_VAL, x1 = -HUGE_VAL, y1 = -HUGE_VAL;
  for (const PlanePoint& q : largest->front()) {
    x0 = std::min(x0, q.x), y0 = std::min(y0, q.y);
    x1 = std::max(x1, q.x), y1 = std::max(y1, q.y);
  }
  const double size = std::max(x1 - x0, y1 - y0);
  a.at = size > 0 ? geos.inscribed_centre(*largest, size / 200) : largest->front().front();
  return a;
}

LinePath line_label_path(const std::vector<std::vector<XY>>& parts) {
  LinePath out;
  const std::vector<XY>* longest = nullptr;
  double longest_length = -1;
  for (const std::vector<XY>& part : parts) {
    double len = 0;
    for (size_t i = 1; i < part.size(); ++i)
      len += std::hypot(part[i].x - part[i - 1].x, part[i].y - part[i - 1].y);
    out.length += len;
    if (len > longest_length) longest_length = len, longest = &part;
  }
  if (!longest || longest->size() < 2) return out;
  double tolerance = longest_length / 500;
  out.points = douglas_peucker(*longest, tolerance);
  while (out.points.size() > 256) {
    tolerance *= 2;
    out.points = douglas_peucker(*longest, tolerance);
  }
  // Segments of at most 1/32 of the part, straight in the tiling's frame as
  // the lines are drawn: a viewer that places glyphs between the path's
  // points on screen then follows the drawn line on a curved globe too.
  const double step = longest_length / 32;
  std::vector<XY> dense;
  for (size_t i = 0; i + 1 < out.points.size(); ++i) {
    const XY a = out.points[i], b = out.points[i + 1];
    const int n = std::max(1, static_cast<int>(std::ceil(std::hypot(b.x - a.x, b.y - a.y) / step)));
    for (int k = 0; k < n; ++k)
      dense.push_back({a.x + (b.x - a.x) * k / n, a.y + (b.y - a.y) * k / n});
  }
  dense.push_back(out.points.back());
  out.points = std::move(dense);
  return out;
}

std::string labels_metadata_json(const std::string& field, const std::string& priority,
                                 int64_t count) {
  return "{\"field\":\"" + tileformat::json_escape(field) + "\",\"priority\":\"" +
         tileformat::json_escape(priority) + "\",\"count\":" + std::to_string(count) + "}";
}

}  // namespace globe
