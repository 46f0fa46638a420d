// Area package builder (see areas_builder.hpp).
#include "areas/areas_builder.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include <strings.h>

#include "areas/area_geometry.hpp"
#include "areas/area_tiles.hpp"
#include "areas/choropleth.hpp"
#include "io/vector_frame.hpp"
#include "io/vector_reader.hpp"
#include "labels/label_candidates.hpp"
#include "lines/line_classes.hpp"
#include "lines/line_plan.hpp"
#include "lines/line_projector.hpp"
#include "runtime/errors.hpp"
#include "shard/line_shard.hpp"
#include "tileformat/feature_table.hpp"
#include "tileformat/label_table.hpp"
#include "tileformat/metadata.hpp"
#include "tileformat/package.hpp"
#include "tileformat/shard_table.hpp"

namespace globe {
namespace {

using tileformat::Bounds;

// `k` colours of the ramp: ColorBrewer's own for that count, else picked
// evenly from the nearest count it has (pretty breaks may give fewer or more
// classes than asked for).
std::vector<std::string> choropleth_colors(const std::string& ramp, int k) {
  if (auto exact = ramp_colors(ramp, k)) return *exact;
  for (const ColorRamp& r : color_ramps()) {
    if (strcasecmp(r.name, ramp.c_str()) != 0) continue;
    const int n = std::clamp(k, r.min_classes, r.max_classes);
    const std::vector<std::string> all = *ramp_colors(ramp, n);
    std::vector<std::string> out;
    for (int i = 0; i < k; ++i)
      out.push_back(all[k == 1 ? size_t(n / 2)
                               : static_cast<size_t>(std::lround(double(i) * (n - 1) / (k - 1)))]);
    return out;
  }
  throw UsageError("--colors " + ramp + ": not a ColorBrewer ramp");
}

class Builder {
 public:
  Builder(const AreasSettings& s, Progress& progress)
      : s_(s), progress_(progress), classes_(s.class_map, s.styles) {}

  AreasSummary run() {
    const auto start = std::chrono::steady_clock::now();
    frame_ = choose_vector_frame(s_.like, s_);
    // Shard 0 holds the features table of a sharded build (as for lines).
    const bool keeps_features = !s_.shard || s_.shard->index == 0;
    VectorReaderOptions ro;
    ro.properties = keeps_features;
    ro.layers = s_.layers;
    ro.where = s_.where;
    ro.class_field = s_.class_field;
    ro.s_srs = s_.s_srs;
    ro.polygons = true;
    if (s_.choropleth) {
      ro.value_fields.push_back(s_.choropleth->field);
      ro.field_options[s_.choropleth->field] = "--choropleth";
      if (!s_.choropleth->denominator.empty()) {
        ro.value_fields.push_back(s_.choropleth->denominator);
        ro.field_options[s_.choropleth->denominator] = "--choropleth";
      }
    }
    if (s_.bbox) ro.filter = Bounds{(*s_.bbox)[0], (*s_.bbox)[1], (*s_.bbox)[2], (*s_.bbox)[3]};
    if (keeps_features)
      label_field_ = request_label_fields(s_.labels, s_.inputs, ro, progress_, &priority_index_);
    VectorReader reader(s_.inputs, ro);
    for (const std::string& table : reader.skipped_tables())
      progress_.note(table + ": no geometry (a table, e.g. QGIS's styles), left out");
    if (frame_.frame == TargetFrame::kProjected && !frame_.target)
      frame_.target = *reader.layers().front().crs;
    std::unique_ptr<tileformat::PackageWriter> writer = create_package(s_, progress_);
    AreaTileOptions o;
    write_package_tiles(s_.output, [&] {
      tileformat::FeatureTableWriter features(*writer);
      std::optional<tileformat::LabelTableWriter> labels;
      if (!label_field_.empty()) labels.emplace(*writer);
      AreaScratch scratch(s_.output + ".scratch-geometry");
      // A shard plans its share from the polygons' outlines, as a line
      // build does from its lines (shard/line_shard.hpp).
      std::optional<GeometryScratch> outlines;
      if (s_.shard) outlines.emplace(s_.output + ".scratch-outlines");
      pass_read(reader, keeps_features ? &features : nullptr,
                labels && !labels->complete() ? &*labels : nullptr, scratch,
                outlines ? &*outlines : nullptr);
      if (labels) label_count_ = labels->count();
      if (const std::string unused = classes_.unused_style(); !unused.empty()) {
        if (!s_.bbox) throw UsageError(unused);
        progress_.note(unused + " in --bbox");
      }
      classify();
      plan_ = plan_lines(s_, frame_, extent_, lengths_, classes_);
      const int buffer = static_cast<int>(std::lround(s_.extent / kLineTilePx * s_.buffer_px));
      plan_.reach.assign(plan_.reach.size(), static_cast<uint32_t>(buffer));  // the tiles' reach
      const LinePlan& plan = plan_;
      tiling_ = plan.tiling;
      area_ = plan.area;
      sum_.min_zoom = plan.min_zoom;
      sum_.max_zoom = plan.max_zoom;
      if (s_.shard) {
        outlines->rewind();
        shard_.emplace(s_, plan, *outlines, sum_.features_kept, progress_);
        tileformat::ShardTableWriter(*writer).put_roots(shard_->plan().roots);
        o.zooms = [this](const AreaFeature& f) { return shard_->zooms_to_cut(outline_of(f)); };
        o.keeps = [this](tileformat::TileId id) { return shard_->keeps(id); };
      }
      writer->checkpoint();  // the features table is committed before any tile
      o.tiling = plan.tiling;
      o.area = plan.area;
      o.min_zoom = plan.min_zoom;
      o.max_zoom = plan.max_zoom;
      o.extent = s_.extent;
      o.buffer = buffer;
      o.simplify_px = s_.simplify_px;
      o.threads = s_.worker_threads();
      if (!feature_class_.empty())
        o.class_of = [this](uint64_t id) { return feature_class_[id - 1]; };
      TileSorter sorter(s_.output + ".scratch-sort", s_.memory_mb << 20);
      AreaTileStats stats;
      cut_area_tiles(scratch, sum_.features_kept, o, sorter, stats, progress_);
      encode_area_tiles(sorter, o, *writer, stats, progress_);
      sum_.polygons = stats.polygons;
      sum_.vertices = stats.vertices;
      sum_.max_zoom_vertices = stats.max_zoom_vertices;
      sum_.dropped_small = stats.dropped_small;
      sum_.spilled_runs = sorter.spilled_runs();
      sum_.spilled_bytes = sorter.spilled_bytes();
    });
    if (writer->tiles_written() == 0 && !shard_)
      throw InputError(s_.inputs[0] + ": no polygon falls in the requested area" +
                       (s_.bbox ? " (check --bbox)" : "") + "; nothing written");
    const tileformat::AreaMetadata meta = metadata(o);
    writer->set_metadata(tileformat::to_metadata(meta));
    if (!label_field_.empty())
      writer->set_metadata("globe:labels",
                           labels_metadata_json(label_field_, s_.labels.priority, label_count_));
    // A shard's metadata is the whole build's, plus the shard keys.
    if (shard_)
      writer->set_metadata(tileformat::to_metadata(
          shard_metadata(s_, shard_->plan(), meta.common.min_zoom, meta.common.center_zoom)));
    commit_package(*writer, s_.output, start, sum_);
    return sum_;
  }

 private:
  // `outlines`: where a shard's planner reads each feature's exterior rings.
  void pass_read(VectorReader& reader, tileformat::FeatureTableWriter* features,
                 tileformat::LabelTableWriter* labels, AreaScratch& scratch,
                 GeometryScratch* outlines) {
    const FrameLonLat to_lonlat(frame_.frame, frame_.target ? &*frame_.target : nullptr);
    std::vector<LineProjector> projectors;
    for (const VectorLayerInfo& l : reader.layers())
      projectors.emplace_back(frame_.frame, *l.crs, frame_.target ? &*frame_.target : nullptr);
    int64_t total = 0;
    for (const VectorLayerInfo& l : reader.layers())
      total += std::max<int64_t>(0, l.feature_count);
    layer_features_.assign(reader.layers().size(), 0);
    progress_.begin("read features", static_cast<uint64_t>(total));
    Geos geos;
    VectorFeature vf;
    while (reader.next(vf)) {
      ++sum_.features_read;
      progress_.advance();
      AreaFeature f;
      for (const auto& rings : vf.polygons)
        add_polygon(rings, projectors[vf.layer], geos, f.polygons);
      if (f.polygons.empty()) {
        ++sum_.features_skipped;
        continue;
      }
      if (!geos.is_valid(f.polygons)) {
        ++sum_.repaired;
        f.polygons = geos.make_valid(f.polygons);
        if (f.polygons.empty()) {
          ++sum_.features_skipped;
          continue;
        }
      }
      const std::string& layer = reader.layers()[vf.layer].name;
      f.class_id = classes_.class_for(layer, vf.class_value);
      f.id = ++sum_.features_kept;
      ++layer_features_[vf.layer];
      if (features && !features->complete())
        features->add(static_cast<int64_t>(f.id), layer, vf.properties_json);
      if (labels) add_label(vf, f, to_lonlat, geos, *labels);
      if (s_.choropleth) {
        double v = vf.values.at(0);
        if (vf.values.size() > 1) v = vf.values[1] != 0 ? v / vf.values[1] : std::nan("");
        values_.push_back(std::isfinite(v) ? v : std::nan(""));
      }
      for (const PlanePolygon& p : f.polygons) {
        const PlaneRing& r = p.front();
        for (size_t i = 0; i < r.size(); ++i) {
          extent_.min_x = std::min(extent_.min_x, r[i].x);
          extent_.min_y = std::min(extent_.min_y, r[i].y);
          extent_.max_x = std::max(extent_.max_x, r[i].x);
          extent_.max_y = std::max(extent_.max_y, r[i].y);
          const PlanePoint& q = r[(i + 1) % r.size()];
          lengths_.add(std::hypot(q.x - r[i].x, q.y - r[i].y));
        }
      }
      scratch.write(f);
      if (outlines) outlines->write(outline_of(f));
    }
    progress_.end();
    for (const VectorLayerInfo& l : reader.layers())
      layers_.push_back(l);
    if (sum_.features_kept == 0) {
      std::string names;
      for (const VectorLayerInfo& l : reader.layers())
        names += (names.empty() ? "" : ", ") + l.source + " layer '" + l.name + "'";
      throw InputError(names + ": no feature with a usable polygon (" +
                       std::to_string(sum_.features_read) + " read, " +
                       std::to_string(sum_.bad_rings) +
                       " invalid or degenerate rings); areas take polygons and multipolygons - "
                       "for lines and points use `globe-vectorize lines` or `points`");
    }
    scratch.rewind();
  }

  // The feature's label at the pole of inaccessibility of its largest part,
  // unless its name is empty.
  void add_label(const VectorFeature& vf, const AreaFeature& f, const FrameLonLat& to_lonlat,
                 Geos& geos, tileformat::LabelTableWriter& labels) {
    const std::string& text = vf.texts.at(0);
    if (text.empty()) return;
    const AreaAnchor a = area_anchor(f.polygons, geos);
    XY ll;
    if (!to_lonlat({a.at.x, a.at.y}, ll)) return;
    tileformat::LabelRecord r;
    r.feature = static_cast<int64_t>(f.id);
    r.text = text;
    r.priority = a.area;
    if (priority_index_ >= 0) {
      const double p = vf.values.at(size_t(priority_index_));
      r.priority = std::isfinite(p) ? p : 0;
    }
    r.lon = ll.x;
    r.lat = ll.y;
    r.placement = tileformat::LabelPlacement::kArea;
    labels.add(r);
  }

  // A feature's exterior rings as a line feature: what the shard planner
  // (and a shard's choice of zooms) reads.
  static ProjectedFeature outline_of(const AreaFeature& f) {
    ProjectedFeature p;
    p.id = f.id;
    for (const PlanePolygon& poly : f.polygons) {
      p.lines.emplace_back();
      for (const PlanePoint& q : poly.front())
        p.lines.back().push_back({q.x, q.y});
    }
    return p;
  }

  // One source polygon, projected and made ready for the tiling.
  void add_polygon(const std::vector<std::vector<XY>>& rings, const LineProjector& projector,
                   Geos& geos, PlaneMultiPolygon& out) {
    PlanePolygon p;
    for (const std::vector<XY>& src : rings) {
      std::vector<XY> ring = src;
      PlaneRing r;
      if (projector.transform_ring(ring)) {
        for (const XY& q : ring)
          r.push_back({q.x, q.y});
      }
      if (r.empty() || !clean_ring(r) || r.size() < 3) {
        ++sum_.bad_rings;
        if (p.empty()) return;  // no exterior: the polygon goes
        continue;               // a hole goes
      }
      p.push_back(std::move(r));
    }
    if (p.empty()) return;
    if (frame_.frame == TargetFrame::kProjected) {
      out.push_back(std::move(p));
      return;
    }
    for (PlanePolygon& piece : wrap_lonlat_polygon(p, geos, sum_.antimeridian_cuts)) {
      for (PlaneRing& r : piece)
        for (PlanePoint& q : r) {
          const XY f = LineProjector::lonlat_to_frame(frame_.frame, {q.x, q.y});
          q = {f.x, f.y};
        }
      out.push_back(std::move(piece));
    }
  }

  // The choropleth's breaks, colours and each feature's class.
  void classify() {
    if (!s_.choropleth) return;
    const ChoroplethSettings& c = *s_.choropleth;
    std::vector<double> finite;
    for (double v : values_)
      if (std::isfinite(v)) finite.push_back(v);
    if (finite.empty())
      throw InputError(s_.inputs[0] + ": --choropleth " + c.field +
                       (c.denominator.empty() ? "" : "/" + c.denominator) +
                       " has no value in any feature; nothing to class");
    breaks_ = class_breaks(finite, c.classes, c.method);
    const int k = static_cast<int>(breaks_.size()) - 1;
    colors_ = choropleth_colors(c.colors, std::max(k, 1));
    feature_class_.resize(values_.size());
    for (size_t i = 0; i < values_.size(); ++i) {
      const int cls = class_of(values_[i], breaks_);
      feature_class_[i] = cls < 0 ? 0 : static_cast<uint32_t>(cls + 1);
      if (cls < 0) ++sum_.no_data;
    }
  }

  tileformat::AreaMetadata metadata(const AreaTileOptions& o) const {
    tileformat::AreaMetadata m;
    m.common = vector_common_metadata(s_, "Areas", tileformat::kAreasFormat, frame_, tiling_,
                                      extent_, area_, sum_.min_zoom, sum_.max_zoom);
    m.extent = s_.extent;
    m.buffer = o.buffer;
    m.simplify_px = s_.simplify_px;
    m.tile_px = kLineTilePx;
    m.features = sum_.features_kept;
    m.classes_json = classes_.json();
    for (size_t i = 0; i < layers_.size(); ++i)
      m.layers.push_back({layers_[i].name, layers_[i].source, layer_features_[i]});
    m.repaired = sum_.repaired;
    if (s_.choropleth) {
      const ChoroplethSettings& c = *s_.choropleth;
      tileformat::Choropleth ch;
      ch.field = c.field;
      ch.denominator = c.denominator;
      ch.method = class_method_name(c.method);
      ch.ramp = c.colors;
      for (size_t i = 0; i + 1 < breaks_.size(); ++i)
        ch.classes.push_back({breaks_[i], breaks_[i + 1], colors_.at(i)});
      if (ch.classes.empty()) ch.classes.push_back({breaks_[0], breaks_[0], colors_.at(0)});
      ch.no_data_color = c.no_data_color;
      ch.no_data = sum_.no_data;
      m.choropleth = std::move(ch);
    }
    return m;
  }

  const AreasSettings& s_;
  Progress& progress_;
  LineClasses classes_;
  VectorFrame frame_;
  tileformat::Tiling tiling_;
  Bounds area_;
  Bounds extent_{1e300, 1e300, -1e300, -1e300};
  LengthHistogram lengths_;
  LinePlan plan_;
  std::optional<LineShard> shard_;
  std::vector<VectorLayerInfo> layers_;
  std::vector<uint64_t> layer_features_;
  std::vector<double> values_, breaks_;
  std::vector<std::string> colors_;
  std::vector<uint32_t> feature_class_;
  AreasSummary sum_;
  std::string label_field_;  // the attribute labels come from ("" none)
  int priority_index_ = -1;  // --priority-field's index in VectorFeature::values
  int64_t label_count_ = 0;
};

}  // namespace

AreasSummary build_areas(const AreasSettings& settings, Progress& progress) {
  return Builder(settings, progress).run();
}

}  // namespace globe
