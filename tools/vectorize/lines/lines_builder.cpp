// Line-cluster package builder (see lines_builder.hpp).
#include "lines/lines_builder.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>

#include "io/geometry_scratch.hpp"
#include "io/vector_reader.hpp"
#include "kit/package_output.hpp"
#include "labels/label_candidates.hpp"
#include "lines/line_classes.hpp"
#include "lines/line_metadata.hpp"
#include "lines/line_plan.hpp"
#include "lines/line_projector.hpp"
#include "lines/line_tiles.hpp"
#include "runtime/errors.hpp"
#include "shard/line_shard.hpp"
#include "tileformat/error.hpp"
#include "tileformat/feature_table.hpp"
#include "tileformat/label_table.hpp"
#include "tileformat/metadata.hpp"
#include "tileformat/package.hpp"
#include "tileformat/shard_table.hpp"
#include "tiles/tile_sorter.hpp"

namespace globe {
namespace {

using tileformat::Bounds;
using tileformat::TileId;

class Builder {
 public:
  Builder(const LinesSettings& s, Progress& progress)
      : s_(s), progress_(progress), threads_(s.worker_threads()), classes_(s.class_map, s.styles) {}

  LinesSummary run() {
    const auto start = std::chrono::steady_clock::now();
    frame_ = choose_vector_frame(s_.like, s_);
    // Shard 0 holds the features table of a sharded build (docs/tileformat.md
    // §10); the other shards need no properties.
    const bool keeps_features = !s_.shard || s_.shard->index == 0;
    VectorReaderOptions ro;
    ro.layers = s_.layers;
    ro.where = s_.where;
    ro.class_field = s_.class_field;
    ro.s_srs = s_.s_srs;
    ro.properties = keeps_features;
    if (s_.bbox) ro.filter = Bounds{(*s_.bbox)[0], (*s_.bbox)[1], (*s_.bbox)[2], (*s_.bbox)[3]};
    if (keeps_features)
      label_field_ = request_label_fields(s_.labels, s_.inputs, ro, progress_, nullptr);
    VectorReader reader(s_.inputs, ro);
    for (const std::string& table : reader.skipped_tables())
      progress_.note(table + ": no geometry (a table, e.g. QGIS's styles), left out");
    if (frame_.frame == TargetFrame::kProjected && !frame_.target)
      frame_.target = *reader.layers().front().crs;  // local tiling in the first input's CRS
    std::unique_ptr<tileformat::PackageWriter> writer = create_package(s_, progress_);
    write_package_tiles(s_.output, [&] {
      // A resumed build reads and cuts the input again (that state is not
      // kept) but keeps the committed features table and tiles. The table
      // (and a shard's table of subtrees) is created and filled in one
      // transaction (committed below), so it is either there and complete
      // or not there at all.
      tileformat::FeatureTableWriter features(*writer);
      std::optional<tileformat::LabelTableWriter> labels;
      if (!label_field_.empty()) labels.emplace(*writer);
      GeometryScratch scratch(s_.output + ".scratch-geometry");
      pass_read(reader, keeps_features ? &features : nullptr,
                labels && !labels->complete() ? &*labels : nullptr, scratch);
      if (labels) label_count_ = labels->count();
      // Within --bbox a class may be absent for good reason: a note then.
      if (const std::string unused = classes_.unused_style(); !unused.empty()) {
        if (!s_.bbox) throw UsageError(unused);
        progress_.note(unused + " in --bbox");
      }
      plan_ = plan_lines(s_, frame_, facts_.extent, lengths_, classes_);
      sum_.min_zoom = plan_.min_zoom;
      sum_.max_zoom = plan_.max_zoom;
      if (s_.shard) {
        shard_.emplace(s_, plan_, scratch, sum_.features_kept, progress_);
        tileformat::ShardTableWriter(*writer).put_roots(shard_->plan().roots);
      }
      writer->checkpoint();  // the features table is committed before any tile
      TileSorter sorter(s_.output + ".scratch-sort", s_.memory_mb << 20);
      const LineTileOptions tiles = tile_options();
      LineTileStats stats;
      cut_line_tiles(scratch, sum_.features_kept, plan_, tiles, sorter, stats, progress_);
      encode_line_tiles(sorter, plan_, tiles, *writer, stats, progress_);
      sum_.segments = stats.segments;
      sum_.max_zoom_segments = stats.max_zoom_segments;
      sum_.points = stats.points;
      sum_.spilled_runs = sorter.spilled_runs();
      sum_.spilled_bytes = sorter.spilled_bytes();
    });
    if (writer->tiles_written() == 0 && !shard_)
      throw InputError(s_.inputs[0] + ": no line or point falls in the requested area" +
                       (s_.bbox ? " (check --bbox)" : "") + "; nothing written");
    // A shard's metadata is the whole build's (its tiles may leave zooms
    // out), plus the shard keys.
    const tileformat::LineMetadata meta = line_metadata(s_, frame_, plan_, classes_, facts_);
    writer->set_metadata(tileformat::to_metadata(meta));
    if (!label_field_.empty())
      writer->set_metadata("globe:labels",
                           labels_metadata_json(label_field_, s_.labels.priority, label_count_));
    if (shard_)
      writer->set_metadata(tileformat::to_metadata(
          shard_metadata(s_, shard_->plan(), meta.common.min_zoom, meta.common.center_zoom)));
    commit_package(*writer, s_.output, start, sum_);
    return sum_;
  }

 private:
  // `features`: the table to fill (none: left empty).
  void pass_read(VectorReader& reader, tileformat::FeatureTableWriter* features,
                 tileformat::LabelTableWriter* labels, GeometryScratch& scratch) {
    const FrameLonLat to_lonlat(frame_.frame, frame_.target ? &*frame_.target : nullptr);
    std::vector<LineProjector> projectors;
    for (const VectorLayerInfo& l : reader.layers())
      projectors.emplace_back(frame_.frame, *l.crs, frame_.target ? &*frame_.target : nullptr);
    int64_t total = 0;
    for (const VectorLayerInfo& l : reader.layers())
      total += std::max<int64_t>(0, l.feature_count);
    facts_.layer_features.assign(reader.layers().size(), 0);
    progress_.begin("read features", static_cast<uint64_t>(total));
    VectorFeature vf;
    ProjectionCounts counts;
    while (reader.next(vf)) {
      ++sum_.features_read;
      progress_.advance();
      ProjectedFeature pf;
      projectors[vf.layer].project_lines(vf.lines, pf.lines, counts);
      for (const XY& p : vf.points) {
        XY q;
        if (projectors[vf.layer].project_point(p, q))
          pf.points.push_back(q);
        else
          ++counts.failed_parts;
      }
      if (pf.lines.empty() && pf.points.empty()) {
        ++sum_.features_skipped;
        continue;
      }
      const std::string& layer = reader.layers()[vf.layer].name;
      pf.class_id = classes_.class_for(layer, vf.class_value);
      pf.id = ++sum_.features_kept;
      facts_.features = sum_.features_kept;
      ++facts_.layer_features[vf.layer];
      if (features && !features->complete())
        features->add(static_cast<int64_t>(pf.id), layer, vf.properties_json);
      if (labels) add_label(vf, pf, to_lonlat, *labels);
      for (const auto& part : pf.lines)
        for (size_t i = 0; i < part.size(); ++i) {
          extend(part[i]);
          if (i) lengths_.add(std::hypot(part[i].x - part[i - 1].x, part[i].y - part[i - 1].y));
        }
      for (const XY& p : pf.points)
        extend(p);
      scratch.write(pf);
    }
    progress_.end();
    sum_.bad_parts = counts.failed_parts + counts.nonfinite_parts + counts.degenerate_parts;
    sum_.antimeridian_cuts = counts.antimeridian_cuts;
    for (const VectorLayerInfo& l : reader.layers())
      facts_.layers.push_back(l);
    if (sum_.features_kept == 0) {
      std::string names;
      for (const VectorLayerInfo& l : reader.layers())
        names += (names.empty() ? "" : ", ") + l.source + " layer '" + l.name + "'";
      throw InputError(names + ": no feature with usable line or point geometry (" +
                       std::to_string(sum_.features_read) + " read, " +
                       std::to_string(sum_.bad_parts) +
                       " invalid or degenerate parts); check --where, --layer and --bbox");
    }
    scratch.rewind();
  }

  // The line's label along its longest part, anchored at that part's middle,
  // unless its name is empty.
  void add_label(const VectorFeature& vf, const ProjectedFeature& pf, const FrameLonLat& to_lonlat,
                 tileformat::LabelTableWriter& labels) {
    const std::string& text = vf.texts.at(0);
    if (text.empty() || pf.lines.empty()) return;
    const LinePath path = line_label_path(pf.lines);
    if (path.points.size() < 2) return;
    tileformat::LabelRecord r;
    r.feature = static_cast<int64_t>(pf.id);
    r.text = text;
    r.priority = path.length;
    if (!s_.labels.priority.empty()) {
      const double p = vf.values.at(0);
      r.priority = std::isfinite(p) ? p : 0;
    }
    double along = 0, half = 0;
    for (size_t i = 1; i < path.points.size(); ++i)
      half += std::hypot(path.points[i].x - path.points[i - 1].x,
                         path.points[i].y - path.points[i - 1].y);
    half /= 2;
    XY mid = path.points.front();
    for (size_t i = 1; i < path.points.size(); ++i) {
      const XY a = path.points[i - 1], b = path.points[i];
      const double len = std::hypot(b.x - a.x, b.y - a.y);
      if (along + len >= half) {
        const double t = len > 0 ? (half - along) / len : 0;
        mid = {a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t};
        break;
      }
      along += len;
    }
    XY ll;
    if (!to_lonlat(mid, ll)) return;
    r.lon = ll.x, r.lat = ll.y;
    for (const XY& p : path.points) {
      if (!to_lonlat(p, ll)) return;
      r.path.push_back(ll.x);
      r.path.push_back(ll.y);
    }
    r.placement = tileformat::LabelPlacement::kLine;
    labels.add(r);
  }

  void extend(XY p) {
    facts_.extent.min_x = std::min(facts_.extent.min_x, p.x);
    facts_.extent.min_y = std::min(facts_.extent.min_y, p.y);
    facts_.extent.max_x = std::max(facts_.extent.max_x, p.x);
    facts_.extent.max_y = std::max(facts_.extent.max_y, p.y);
  }

  LineTileOptions tile_options() const {
    LineTileOptions o;
    o.extent = s_.extent;
    o.cluster_grid = s_.cluster_grid;
    o.simplify_px = s_.simplify_px;
    o.threads = threads_;
    if (shard_) {
      o.zooms = [this](const ProjectedFeature& f) { return shard_->zooms_to_cut(f); };
      o.keeps = [this](tileformat::TileId id) { return shard_->keeps(id); };
    }
    return o;
  }

  const LinesSettings& s_;
  Progress& progress_;
  const int threads_;
  LineClasses classes_;
  VectorFrame frame_;
  LineFacts facts_;
  LengthHistogram lengths_;
  LinePlan plan_;
  std::optional<LineShard> shard_;
  LinesSummary sum_;
  std::string label_field_;  // the attribute labels come from ("" none)
  int64_t label_count_ = 0;
};

}  // namespace

LinesSummary build_lines(const LinesSettings& settings, Progress& progress) {
  return Builder(settings, progress).run();
}

}  // namespace globe
