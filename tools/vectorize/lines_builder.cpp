// Line-cluster package builder (see lines_builder.hpp).
#include "lines_builder.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <numbers>
#include <sstream>
#include <thread>

#include "errors.hpp"
#include "line_classes.hpp"
#include "line_projector.hpp"
#include "package_output.hpp"
#include "parallel_batches.hpp"
#include "scratch_file.hpp"
#include "tile_cutter.hpp"
#include "tile_sorter.hpp"
#include "tileformat/blob_header.hpp"
#include "tileformat/byte_io.hpp"
#include "tileformat/error.hpp"
#include "tileformat/feature_table.hpp"
#include "tileformat/json.hpp"
#include "tileformat/line_clusters.hpp"
#include "tileformat/line_tile.hpp"
#include "tileformat/metadata.hpp"
#include "tileformat/package.hpp"
#include "vector_reader.hpp"

namespace globe {
namespace {

using tileformat::Bounds;
using tileformat::TileId;
using tileformat::Tiling;

constexpr double kAntialiasPx = 1.0;
constexpr double kTilePx = 256.0;  // nominal display size of a tile (docs/lines.md)
constexpr int kDefaultMaxZoomCap = 18;
constexpr int kPointsOnlyMaxZoom = 14;

// Pass-1 output: projected features, appended and read back in order, one
// scratch record each: id, class, the parts' vertex counts and coordinates
// (f64), then the points.
class GeometryScratch {
 public:
  explicit GeometryScratch(std::string path) : file_(std::move(path)) {}
  void write(const ProjectedFeature& f) {
    tileformat::ByteWriter w;
    w.u64(f.id);
    w.u32(f.class_id);
    w.u32(static_cast<uint32_t>(f.lines.size()));
    w.u32(static_cast<uint32_t>(f.points.size()));
    auto put_xy = [&](const XY& p) {
      w.f64(p.x);
      w.f64(p.y);
    };
    for (const auto& part : f.lines) {
      w.u32(static_cast<uint32_t>(part.size()));
      for (const XY& p : part)
        put_xy(p);
    }
    for (const XY& p : f.points)
      put_xy(p);
    file_.append(w.take());
  }
  void rewind() { file_.rewind(); }
  bool read(ProjectedFeature& f) {
    if (!file_.next(buffer_)) return false;
    tileformat::ByteReader r(buffer_, file_.path() + ": scratch feature", "scratch");
    f.id = r.u64();
    f.class_id = r.u32();
    f.lines.resize(r.u32());
    f.points.resize(r.u32());
    auto get_xy = [&](XY& p) {
      p.x = r.f64();
      p.y = r.f64();
    };
    for (auto& part : f.lines) {
      part.resize(r.u32());
      for (XY& p : part)
        get_xy(p);
    }
    for (XY& p : f.points)
      get_xy(p);
    r.expect_end();
    return true;
  }

 private:
  ScratchFile file_;
  std::vector<uint8_t> buffer_;
};

// Segment lengths on a log scale (quarter octaves), for the median.
class LengthHistogram {
 public:
  void add(double len) {
    if (!(len > 0)) return;
    const int bin = std::clamp(static_cast<int>(std::floor(4 * std::log2(len))) + kOffset, 0,
                               int(bins_.size()) - 1);
    ++bins_[bin];
    ++count_;
  }
  uint64_t count() const { return count_; }
  double median() const {
    uint64_t seen = 0;
    for (size_t b = 0; b < bins_.size(); ++b) {
      seen += bins_[b];
      if (2 * seen >= count_) return std::exp2((int(b) - kOffset + 0.5) / 4.0);
    }
    return 0;
  }

 private:
  static constexpr int kOffset = 200;
  std::array<uint64_t, 401> bins_{};
  uint64_t count_ = 0;
};

class Builder {
 public:
  Builder(const LinesSettings& s, Progress& progress)
      : s_(s), progress_(progress), threads_(s.worker_threads()), classes_(s.class_map, s.styles) {}

  LinesSummary run() {
    const auto start = std::chrono::steady_clock::now();
    choose_frame();
    VectorReaderOptions ro{s_.layers, s_.where, s_.class_field, std::nullopt, s_.s_srs};
    if (s_.bbox) ro.filter = Bounds{(*s_.bbox)[0], (*s_.bbox)[1], (*s_.bbox)[2], (*s_.bbox)[3]};
    VectorReader reader(s_.inputs, ro);
    if (frame_ == TargetFrame::kProjected && !target_)
      target_ = *reader.layers().front().crs;  // local tiling in the first input's CRS
    std::unique_ptr<tileformat::PackageWriter> writer = create_package(s_, progress_);
    try {
      // A resumed build reads and cuts the input again (that state is not
      // kept) but keeps the committed features table and tiles. The table
      // is created and filled in one transaction (committed below), so it
      // is either there and complete or not there at all.
      tileformat::FeatureTableWriter features(*writer);
      GeometryScratch scratch(s_.output + ".scratch-geometry");
      pass_read(reader, features, scratch);
      writer->checkpoint();  // the features table is committed before any tile
      plan();
      TileSorter sorter(s_.output + ".scratch-sort", s_.memory_mb << 20);
      pass_cut(scratch, sorter);
      pass_encode(sorter, *writer);
      sum_.spilled_runs = sorter.spilled_runs();
      sum_.spilled_bytes = sorter.spilled_bytes();
    } catch (const tileformat::PackageError& e) {
      throw build_write_error(s_.output, e);
    } catch (const OutputError& e) {  // scratch files
      throw build_write_error(s_.output, e);
    }
    if (writer->tiles_written() == 0)
      throw InputError(s_.inputs[0] + ": no line or point falls in the requested area" +
                       (s_.bbox ? " (check --bbox)" : "") + "; nothing written");
    write_metadata(*writer);
    sum_.tiles = writer->tiles_written();
    sum_.unique_blobs = writer->unique_blobs();
    sum_.file_bytes = commit_package(*writer, s_.output);
    sum_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return sum_;
  }

 private:
  void choose_frame() {
    if (!s_.like.empty()) {
      tileformat::PackageReader like(s_.like);
      tiling_ = Tiling::from_metadata(like.metadata());
      tiling_known_ = true;
      if (tiling_.scheme == tileformat::Scheme::kLocal) {
        frame_ = TargetFrame::kProjected;
        target_ = SpatialRef::from_wkt(tiling_.crs, s_.like);
      } else {
        frame_ = tiling_.scheme == tileformat::Scheme::kGeodetic ? TargetFrame::kGeodetic
                                                                 : TargetFrame::kWebMercator;
      }
      return;
    }
    if (s_.tiling == tileformat::Scheme::kWebMercator) {
      frame_ = TargetFrame::kWebMercator;
      tiling_ = Tiling::webmercator();
      tiling_known_ = true;
    } else if (s_.tiling == tileformat::Scheme::kGeodetic) {
      frame_ = TargetFrame::kGeodetic;
      tiling_ = Tiling::geodetic();
      tiling_known_ = true;
    } else {
      frame_ = TargetFrame::kProjected;
      if (!s_.t_srs.empty()) target_ = SpatialRef::from_user_input(s_.t_srs, "--t_srs");
    }
    if (!s_.t_srs.empty() && frame_ != TargetFrame::kProjected)
      throw UsageError("--t_srs applies to --tiling local only");
  }

  void pass_read(VectorReader& reader, tileformat::FeatureTableWriter& features,
                 GeometryScratch& scratch) {
    std::vector<LineProjector> projectors;
    for (const VectorLayerInfo& l : reader.layers())
      projectors.emplace_back(frame_, *l.crs, target_ ? &*target_ : nullptr);
    int64_t total = 0;
    for (const VectorLayerInfo& l : reader.layers())
      total += std::max<int64_t>(0, l.feature_count);
    layer_kept_.assign(reader.layers().size(), 0);
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
      ++layer_kept_[vf.layer];
      if (!features.complete())
        features.add(static_cast<int64_t>(pf.id), layer, vf.properties_json);
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
      layers_.push_back(l);
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

  void extend(XY p) {
    extent_.min_x = std::min(extent_.min_x, p.x);
    extent_.min_y = std::min(extent_.min_y, p.y);
    extent_.max_x = std::max(extent_.max_x, p.x);
    extent_.max_y = std::max(extent_.max_y, p.y);
  }

  // Tiling (local), zoom range, area and the reach of every zoom.
  void plan() {
    if (!tiling_known_) {
      const double span = std::max({extent_.width(), extent_.height(), 1e-9});
      const double root = std::exp2(std::ceil(std::log2(span)));
      tiling_ = Tiling::local(target_->wkt2(), extent_.min_x, extent_.max_y, root);
    }
    area_ = tiling_.extent();
    if (s_.bbox) {
      const auto& b = *s_.bbox;
      Bounds box;
      if (frame_ == TargetFrame::kProjected) {
        CoordTransform t(SpatialRef::from_user_input("EPSG:4326", "--bbox"), *target_);
        if (!t.transform_bounds({b[0], b[1], b[2], b[3]}, box))
          throw UsageError("--bbox cannot be expressed in the tiling CRS");
      } else {
        const XY lo = LineProjector::lonlat_to_frame(frame_, {b[0], b[1]});
        const XY hi = LineProjector::lonlat_to_frame(frame_, {b[2], b[3]});
        box = {lo.x, lo.y, hi.x, hi.y};
      }
      area_ = {std::max(area_.min_x, box.min_x), std::max(area_.min_y, box.min_y),
               std::min(area_.max_x, box.max_x), std::min(area_.max_y, box.max_y)};
    }
    min_zoom_ = s_.min_zoom.value_or(0);
    if (s_.max_zoom) {
      max_zoom_ = *s_.max_zoom;
    } else if (lengths_.count() == 0) {
      max_zoom_ = std::max(min_zoom_, kPointsOnlyMaxZoom);
    } else {
      // The first zoom where the median segment spans 4 pixels: deeper zooms
      // would add no shape, only magnify (the viewer overzooms instead).
      const double median = lengths_.median();
      max_zoom_ = min_zoom_;
      while (max_zoom_ < kDefaultMaxZoomCap && median < 4 * tiling_.tile_size(max_zoom_) / kTilePx)
        ++max_zoom_;
    }
    if (min_zoom_ > max_zoom_)
      throw UsageError("--min-zoom " + std::to_string(min_zoom_) + " is above the max zoom " +
                       std::to_string(max_zoom_));
    // Reach: the widest class (half width + casing) plus antialiasing, in
    // tile units, for a tile drawn at its nominal 256 px.
    const double units_per_px = s_.extent / kTilePx;
    double crs_per_m = 1;
    if (frame_ != TargetFrame::kProjected) {
      const XY lo = LineProjector::frame_to_lonlat(frame_, {extent_.min_x, extent_.min_y});
      const XY hi = LineProjector::frame_to_lonlat(frame_, {extent_.max_x, extent_.max_y});
      const double lat = std::min(85.0, std::max(std::abs(lo.y), std::abs(hi.y)));
      const double c = std::cos(lat * std::numbers::pi / 180);
      crs_per_m = frame_ == TargetFrame::kWebMercator ? 1 / c : 1 / (111320.0 * c);
    } else {
      crs_per_m = 1 / target_->linear_units();
    }
    reach_.assign(max_zoom_ + 1, 0);
    for (int z = min_zoom_; z <= max_zoom_; ++z) {
      const double units_per_crs = s_.extent / tiling_.tile_size(z);
      const double half = std::max(classes_.max_half_px() * units_per_px,
                                   classes_.max_half_m() * crs_per_m * units_per_crs);
      reach_[z] =
          std::min<uint32_t>(static_cast<uint32_t>(std::ceil(half + kAntialiasPx * units_per_px)),
                             static_cast<uint32_t>(s_.extent / 4));
    }
    sum_.min_zoom = min_zoom_;
    sum_.max_zoom = max_zoom_;
  }

  void pass_cut(GeometryScratch& scratch, TileSorter& sorter) {
    const TileCutter cutter(tiling_, s_.extent, s_.simplify_px, area_);
    struct Result {
      std::vector<Emission> emissions;
      CutStats stats;
    };
    progress_.begin("cut into tiles", sum_.features_kept);
    std::vector<ProjectedFeature> batch;
    for (bool more = true; more;) {
      batch.clear();
      size_t vertices = 0;
      while (batch.size() < 4096 && vertices < (1u << 20)) {
        ProjectedFeature f;
        if (!scratch.read(f)) {
          more = false;
          break;
        }
        for (const auto& p : f.lines)
          vertices += p.size();
        batch.push_back(std::move(f));
      }
      parallel_batches<NoInputs, Result>(
          batch.size(), threads_, batch.size(), [](size_t, size_t) { return NoInputs{}; },
          [&](size_t i, int, const NoInputs&) {
            Result r;
            uint32_t sub = 0;
            for (int z = min_zoom_; z <= max_zoom_; ++z)
              cutter.cut(batch[i], z, reach_[z], z == max_zoom_, sub, r.emissions, r.stats);
            return r;
          },
          [&](size_t i, Result&& r) {
            for (const Emission& e : r.emissions)
              sorter.add(e.key, batch[i].id, e.sub, e.piece.to_bytes());
            cut_.runs += r.stats.runs;
            cut_.collapsed_runs += r.stats.collapsed_runs;
            progress_.advance();
          },
          [](size_t) {});
    }
    progress_.end();
    sorter.finish();
  }

  std::vector<uint8_t> encode_tile(const TileGroup& group, uint64_t& segments,
                                   uint64_t& points) const {
    const TileId id = key_tile(group.key);
    tileformat::LineTile t;
    t.extent = static_cast<uint32_t>(s_.extent);
    t.grid = static_cast<uint32_t>(s_.cluster_grid);
    t.reach = reach_[id.z];
    for (const TileRecord& rec : group.records) {
      if (t.feature_ids.empty() || t.feature_ids.back() != rec.seq)
        t.feature_ids.push_back(rec.seq);
      const uint32_t feature = static_cast<uint32_t>(t.feature_ids.size() - 1);
      TilePiece piece = TilePiece::from_bytes(group.payload(rec));
      if (piece.point) {
        t.points.push_back({feature, piece.class_id, piece.vertices.at(0)});
        continue;
      }
      t.runs.push_back({feature, piece.class_id, static_cast<uint32_t>(t.vertices.size()),
                        static_cast<uint32_t>(piece.vertices.size())});
      t.vertices.insert(t.vertices.end(), piece.vertices.begin(), piece.vertices.end());
    }
    tileformat::build_cluster_grid(t);
    segments = t.segment_count();
    points = t.points.size();
    return tileformat::encode_line_tile(t);
  }

  void pass_encode(TileSorter& sorter, tileformat::PackageWriter& writer) {
    struct Encoded {
      std::vector<uint8_t> blob;
      uint64_t segments = 0, points = 0;
    };
    progress_.begin("encode tiles", sorter.records());
    // Tiles are put in key order: those a resumed package holds come first.
    uint64_t skip = writer.resumed() ? writer.tiles_written() : 0;
    std::vector<TileGroup> groups;
    for (bool more = true; more;) {
      groups.clear();
      size_t bytes = 0;
      while (groups.size() < size_t(64 * threads_) && bytes < (16u << 20)) {
        TileGroup g;
        if (!sorter.next_group(g)) {
          more = false;
          break;
        }
        if (skip > 0) {
          --skip;
          progress_.advance(g.records.size());
          continue;
        }
        bytes += g.bytes.size() + g.records.size() * sizeof(TileRecord);
        groups.push_back(std::move(g));
      }
      parallel_batches<NoInputs, Encoded>(
          groups.size(), threads_, groups.size(), [](size_t, size_t) { return NoInputs{}; },
          [&](size_t i, int, const NoInputs&) {
            Encoded e;
            e.blob = encode_tile(groups[i], e.segments, e.points);
            return e;
          },
          [&](size_t i, Encoded&& e) {
            writer.put_tile(key_tile(groups[i].key), e.blob);
            sum_.segments += e.segments;
            sum_.points += e.points;
            if (key_tile(groups[i].key).z == max_zoom_) sum_.max_zoom_segments += e.segments;
            progress_.advance(groups[i].records.size());
          },
          [](size_t) {});
    }
    progress_.end();
  }

  void write_metadata(tileformat::PackageWriter& w) const {
    // Longitude/latitude bounds of the data (clipped to the area).
    const Bounds b{std::max(extent_.min_x, area_.min_x), std::max(extent_.min_y, area_.min_y),
                   std::min(extent_.max_x, area_.max_x), std::min(extent_.max_y, area_.max_y)};
    Bounds ll;
    if (frame_ == TargetFrame::kProjected) {
      CoordTransform t(*target_, SpatialRef::from_user_input("EPSG:4326", "bounds"));
      if (!t.transform_bounds(b, ll)) ll = {-180, -85, 180, 85};
    } else {
      const XY lo = LineProjector::frame_to_lonlat(frame_, {b.min_x, b.min_y});
      const XY hi = LineProjector::frame_to_lonlat(frame_, {b.max_x, b.max_y});
      ll = {lo.x, lo.y, hi.x, hi.y};
    }
    tileformat::LineMetadata m;
    tileformat::CommonMetadata& c = m.common;
    for (const auto& input : s_.inputs) {
      std::error_code ec;
      const auto bytes = std::filesystem::file_size(input, ec);
      c.inputs.push_back({input, ec ? 0 : static_cast<uint64_t>(bytes)});
    }
    c.name = std::filesystem::path(s_.output).stem().string();
    c.format = tileformat::kLineClustersFormat;
    c.type = "overlay";
    c.description = tileformat::build_description("Line clusters", "globe-vectorize", c.inputs);
    c.lonlat = ll;
    c.min_zoom = min_zoom_;
    c.max_zoom = max_zoom_;
    c.center_zoom = tiling_.view_zoom(b, min_zoom_, max_zoom_);
    c.tiling = tiling_;
    c.generator = "globe-vectorize " GLOBE_VERSION;
    c.command_line = s_.command_line;
    m.extent = s_.extent;
    m.cluster_grid = s_.cluster_grid;
    m.simplify_px = s_.simplify_px;
    m.tile_px = kTilePx;
    m.features = sum_.features_kept;
    m.classes_json = classes_.json();
    for (size_t i = 0; i < layers_.size(); ++i)
      m.layers.push_back({layers_[i].name, layers_[i].source, layer_kept_[i]});
    w.set_metadata(tileformat::to_metadata(m));
  }

  const LinesSettings& s_;
  Progress& progress_;
  const int threads_;
  LineClasses classes_;
  TargetFrame frame_ = TargetFrame::kWebMercator;
  std::optional<SpatialRef> target_;
  Tiling tiling_;
  bool tiling_known_ = false;
  Bounds extent_{1e300, 1e300, -1e300, -1e300};  // data, tiling CRS
  Bounds area_;
  LengthHistogram lengths_;
  std::vector<VectorLayerInfo> layers_;
  std::vector<uint64_t> layer_kept_;
  int min_zoom_ = 0, max_zoom_ = 0;
  std::vector<uint32_t> reach_;
  CutStats cut_;
  LinesSummary sum_;
};

}  // namespace

LinesSummary build_lines(const LinesSettings& settings, Progress& progress) {
  return Builder(settings, progress).run();
}

}  // namespace globe
