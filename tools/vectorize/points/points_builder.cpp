// Point package builder (see points_builder.hpp).
#include "points/points_builder.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <sstream>

#include "io/vector_frame.hpp"
#include "io/vector_reader.hpp"
#include "kit/package_output.hpp"
#include "kit/parallel_batches.hpp"
#include "labels/label_candidates.hpp"
#include "lines/line_projector.hpp"
#include "points/point_aggregation.hpp"
#include "runtime/errors.hpp"
#include "tileformat/error.hpp"
#include "tileformat/feature_table.hpp"
#include "tileformat/label_table.hpp"
#include "tileformat/metadata.hpp"
#include "tileformat/package.hpp"
#include "tileformat/point_tile.hpp"
#include "tiles/tile_cutter.hpp"

namespace globe {
namespace {

using tileformat::Bounds;
using tileformat::TileId;

// The nominal display size of a tile (as for lines, docs/lines.md).
constexpr double kTilePx = 256.0;
// The default finest zoom: the first where at most 1 % of the places have
// another within --merge-px, or where tiles hold fewer than 2 places on
// average (deeper zooms would add about a tile per place to split the few
// left), and never finer than this.
constexpr int kDefaultMaxZoomCap = 16;
constexpr double kCrowdedShare = 0.01;
constexpr double kFewestPlacesPerTile = 2;
// Point tiles are small and many: zstd level 3 costs 15 % less CPU than 9
// for 1.5 % more bytes (measured on 100 k places).
constexpr int kZstdLevel = 3;

std::string number_text(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

class Builder {
 public:
  Builder(const PointsSettings& s, Progress& progress)
      : s_(s),
        progress_(progress),
        threads_(s.worker_threads()),
        fields_(static_cast<int>(s.fields.size())) {}

  PointsSummary run() {
    const auto start = std::chrono::steady_clock::now();
    frame_ = choose_vector_frame(s_.like, s_);
    VectorReaderOptions ro;
    ro.layers = s_.layers;
    ro.where = s_.where;
    ro.s_srs = s_.s_srs;
    ro.value_fields = s_.fields;
    for (const std::string& f : s_.fields)
      ro.field_options[f] = "--fields";
    ro.xy = s_.xy;
    if (!s_.label_field.empty()) {
      ro.text_fields.push_back(s_.label_field);
      ro.field_options[s_.label_field] = "--label-field";
    }
    if (!s_.priority_field.empty()) {
      if (s_.label_field.empty())
        throw UsageError("--priority-field ranks labels: add --label-field");
      ro.value_fields.push_back(s_.priority_field);
      ro.field_options[s_.priority_field] = "--priority-field";
    }
    if (s_.bbox) ro.filter = Bounds{(*s_.bbox)[0], (*s_.bbox)[1], (*s_.bbox)[2], (*s_.bbox)[3]};
    VectorReader reader(s_.inputs, ro);
    for (const std::string& table : reader.skipped_tables())
      progress_.note(table + ": no geometry (a table, e.g. QGIS's styles), left out");
    check_layers(reader);
    if (frame_.frame == TargetFrame::kProjected && !frame_.target)
      frame_.target = *reader.layers().front().crs;  // local tiling in the first input's CRS
    std::unique_ptr<tileformat::PackageWriter> writer = create_package(s_, progress_);
    write_package_tiles(s_.output, [&] {
      // A resumed build reads and aggregates again but keeps the committed
      // features table (filled in the first transaction) and tiles.
      tileformat::FeatureTableWriter features(*writer);
      std::optional<tileformat::LabelTableWriter> labels;
      if (!s_.label_field.empty()) labels.emplace(*writer);
      auto read_places =
          std::make_unique<PlaceSorter>(s_.output + ".scratch-read", s_.memory_mb << 20, fields_);
      read(reader, features, labels && !labels->complete() ? &*labels : nullptr, *read_places);
      if (labels) label_count_ = labels->count();
      writer->checkpoint();
      tiling_ = frame_tiling(frame_, extent_);
      area_ = frame_area(frame_, tiling_, s_);
      if (tiling_.wraps_x()) wrap_ = {tiling_.extent().width(), tiling_.extent().min_x};
      auto source = std::make_unique<PlaceFile>(s_.output + ".scratch-places", fields_);
      keep_area(*read_places, *source);
      read_places.reset();  // its last run, in memory
      plan_zooms(*source);
      skip_ = writer->resumed() ? writer->tiles_written() : 0;
      // The finest zoom: the source places merged at its radius; then each
      // zoom's tiles, while its places merge into the next coarser zoom's.
      auto level = level_sorter(sum_.max_zoom);
      source->rewind();
      sweep(*source, sum_.places, std::nullopt, sum_.max_zoom, level.get(), *writer);
      source.reset();
      for (int z = sum_.max_zoom;; --z) {
        level->finish();
        auto coarser = z > sum_.min_zoom ? level_sorter(z - 1) : nullptr;
        sweep(*level, level->size(), z,
              z > sum_.min_zoom ? std::optional<int>(z - 1) : std::nullopt, coarser.get(), *writer);
        if (z == sum_.min_zoom) {
          sum_.coarsest_places = level->size();
          break;
        }
        level = std::move(coarser);
      }
    });
    writer->set_metadata(tileformat::to_metadata(metadata()));
    if (!s_.label_field.empty())
      writer->set_metadata("globe:labels",
                           labels_metadata_json(s_.label_field, s_.priority_field, label_count_));
    commit_package(*writer, s_.output, start, sum_);
    return sum_;
  }

 private:
  // The place's label (its name beside its chart), unless the name is empty
  // or the place lies outside --bbox.
  void add_label(const VectorFeature& vf, uint64_t id, XY at, const FrameLonLat& to_lonlat,
                 tileformat::LabelTableWriter& labels) {
    const std::string& text = vf.texts.at(0);
    XY ll;
    if (text.empty() || !to_lonlat(at, ll)) return;
    if (s_.bbox && (ll.x < (*s_.bbox)[0] || ll.x > (*s_.bbox)[2] || ll.y < (*s_.bbox)[1] ||
                    ll.y > (*s_.bbox)[3]))
      return;
    tileformat::LabelRecord r;
    r.feature = static_cast<int64_t>(id);
    r.text = text;
    if (!s_.priority_field.empty()) {
      r.priority = vf.values.at(size_t(fields_));
    } else {
      for (int f = 0; f < fields_; ++f)
        r.priority += std::isfinite(vf.values[size_t(f)]) ? vf.values[size_t(f)] : 0;
    }
    if (!std::isfinite(r.priority)) r.priority = 0;
    r.lon = ll.x;
    r.lat = ll.y;
    r.placement = tileformat::LabelPlacement::kPoint;
    labels.add(r);
  }

  void check_layers(const VectorReader& reader) const {
    for (const VectorLayerInfo& l : reader.layers()) {
      const std::string where = l.source + " layer '" + l.name + "'";
      if (l.geometry == LayerGeometry::kLines || l.geometry == LayerGeometry::kPolygons)
        throw InputError(where + " holds " +
                         (l.geometry == LayerGeometry::kLines ? "lines" : "polygons") +
                         "; globe-vectorize points draws charts at points (lines and outlines: "
                         "globe-vectorize lines)");
      if (!s_.label_field.empty() &&
          std::find(l.fields.begin(), l.fields.end(), s_.label_field) == l.fields.end()) {
        std::string names;
        for (const std::string& f : l.fields)
          names += (names.empty() ? "" : ", ") + f;
        throw UsageError("--label-field '" + s_.label_field + "': " + where +
                         " has no such field; its fields are: " + names);
      }
    }
  }

  void read(VectorReader& reader, tileformat::FeatureTableWriter& features,
            tileformat::LabelTableWriter* labels, PlaceSorter& out) {
    const FrameLonLat to_lonlat(frame_.frame, frame_.target ? &*frame_.target : nullptr);
    std::vector<LineProjector> projectors;
    for (const VectorLayerInfo& l : reader.layers())
      projectors.emplace_back(frame_.frame, *l.crs, frame_.target ? &*frame_.target : nullptr);
    int64_t total = 0;
    for (const VectorLayerInfo& l : reader.layers())
      total += std::max<int64_t>(0, l.feature_count);
    progress_.begin("read places", static_cast<uint64_t>(total));
    VectorFeature vf;
    Place place;
    place.sums.resize(size_t(fields_));
    while (reader.next(vf)) {
      ++sum_.features_read;
      progress_.advance();
      const VectorLayerInfo& layer = reader.layers()[vf.layer];
      const std::string where =
          layer.source + " layer '" + layer.name + "' feature " + std::to_string(vf.fid);
      if (!vf.lines.empty())
        throw InputError(where +
                         " is a line or polygon; globe-vectorize points takes point features "
                         "(lines and outlines: globe-vectorize lines)");
      if (vf.points.empty()) {
        ++sum_.skipped_no_point;
        continue;
      }
      // A multipoint stands for one place: its mean.
      XY at{0, 0};
      bool projected = true;
      for (const XY& p : vf.points) {
        XY q;
        projected = projected && projectors[vf.layer].project_point(p, q);
        at = {at.x + q.x, at.y + q.y};
      }
      if (!projected) {
        ++sum_.skipped_unprojected;
        continue;
      }
      at = {at.x / double(vf.points.size()), at.y / double(vf.points.size())};
      for (int f = 0; f < fields_; ++f) {
        double v = vf.values[f];
        if (std::isnan(v)) {
          ++sum_.empty_values;
          v = 0;
        }
        if (!std::isfinite(v))
          throw InputError(where + ": " + s_.fields[f] + " is " + number_text(v) +
                           "; values must be finite numbers");
        if (v < 0 && s_.sign == ValueSign::kNonNegative)
          throw InputError(where + ": " + s_.fields[f] + " is " + number_text(v) +
                           ", a negative value; pies and stacked bars show shares of a whole. "
                           "Pass --signed to keep negative values (bar and column charts)");
        place.sums[f] = v;
      }
      const uint64_t id = ++kept_;
      if (!features.complete())
        features.add(static_cast<int64_t>(id), layer.name, vf.properties_json);
      if (labels) add_label(vf, id, at, to_lonlat, *labels);
      place.x = at.x;
      place.y = at.y;
      place.id = id;
      out.add(place);
      extent_ = {std::min(extent_.min_x, at.x), std::min(extent_.min_y, at.y),
                 std::max(extent_.max_x, at.x), std::max(extent_.max_y, at.y)};
    }
    progress_.end();
    if (out.size() == 0) {
      std::string names;
      for (const VectorLayerInfo& l : reader.layers())
        names += (names.empty() ? "" : ", ") + l.source + " layer '" + l.name + "'";
      throw InputError(names + ": no place with a usable point (" +
                       std::to_string(sum_.features_read) + " features read, " +
                       std::to_string(sum_.skipped_no_point) + " without geometry, " +
                       std::to_string(sum_.skipped_unprojected) +
                       " not transformable); check --where, --layer, --xy and --bbox");
    }
  }

  // Drops the places outside --bbox (the tiling's extent holds every
  // projected place), keeping the rest in sweep order.
  void keep_area(PlaceSorter& in, PlaceFile& out) {
    progress_.begin("sort places", 0);
    in.finish();
    Place p;
    while (in.next(p)) {
      if (p.x < area_.min_x || p.x > area_.max_x || p.y < area_.min_y || p.y > area_.max_y) {
        ++sum_.skipped_outside;
        continue;
      }
      out.append(p);
    }
    out.rewind();
    progress_.end();
    if (out.size() == 0)
      throw InputError(s_.inputs[0] + ": no place falls in the requested area (check --bbox); " +
                       "nothing written");
    sum_.places = out.size();
  }

  void plan_zooms(PlaceFile& source) {
    sum_.min_zoom = s_.min_zoom.value_or(0);
    if (s_.max_zoom) {
      sum_.max_zoom = *s_.max_zoom;
    } else {
      // The share of crowded places and the places per tile fall as the
      // zoom grows: bisect (each step two passes over the sorted places).
      int lo = sum_.min_zoom, hi = std::max(sum_.min_zoom, kDefaultMaxZoomCap);
      progress_.begin("choose the finest zoom", 0);
      while (lo < hi) {
        const int mid = (lo + hi) / 2;
        source.rewind();
        bool fine = double(sum_.places) < kFewestPlacesPerTile * double(tiles_holding(source, mid));
        if (!fine) {
          source.rewind();
          const int bz = band_zoom(mid);
          fine = crowded_share(source, radius(mid), wrap_,
                               [&](const Place& p) { return band_of(p, bz); }) <= kCrowdedShare;
        }
        if (fine)
          hi = mid;
        else
          lo = mid + 1;
      }
      progress_.end();
      sum_.max_zoom = lo;
    }
    if (sum_.min_zoom > sum_.max_zoom)
      throw UsageError("--min-zoom " + std::to_string(sum_.min_zoom) + " is above the max zoom " +
                       std::to_string(sum_.max_zoom));
  }

  // A place's tile row at zoom z (clamped to the tiling) and column.
  uint64_t tile_row(const Place& p, int z) const {
    const double ny = double(tiling_.tiles_y(z));
    return uint64_t(
        std::clamp(std::floor((tiling_.origin_y - p.y) / tiling_.tile_size(z)), 0.0, ny - 1));
  }
  uint64_t tile_column(const Place& p, int z) const {
    const double nx = double(tiling_.tiles_x(z));
    return uint64_t(
        std::clamp(std::floor((p.x - tiling_.origin_x) / tiling_.tile_size(z)), 0.0, nx - 1));
  }

  // How many tiles of zoom z the places (in sweep order) lie in.
  uint64_t tiles_holding(PlaceSource& places, int z) const {
    uint64_t tiles = 0, row = UINT64_MAX;
    std::vector<uint64_t> columns;
    const auto count_row = [&] {
      std::sort(columns.begin(), columns.end());
      tiles += uint64_t(std::unique(columns.begin(), columns.end()) - columns.begin());
      columns.clear();
    };
    Place p;
    size_t unique_size = 0;
    while (places.next(p)) {
      const uint64_t r = tile_row(p, z);
      if (r != row) {
        count_row();
        row = r;
        unique_size = 0;
      }
      columns.push_back(tile_column(p, z));
      if (columns.size() > 2 * unique_size + 4096) {  // at most the row's tiles held
        std::sort(columns.begin(), columns.end());
        columns.erase(std::unique(columns.begin(), columns.end()), columns.end());
        unique_size = columns.size();
      }
    }
    count_row();
    return tiles;
  }

  double radius(int z) const { return s_.merge_px * tiling_.tile_size(z) / kTilePx; }

  // The zoom whose tile rows are the bands for merging at zoom z: the finest
  // whose rows are at least the radius high (so places two bands apart are
  // never neighbours); below 0 when even the roots are lower (one band).
  int band_zoom(int z) const {
    const double r = radius(z);
    int bz = z;
    if (std::ldexp(tiling_.tile_size(0), -bz) >= r) {
      while (bz < z + 24 && std::ldexp(tiling_.tile_size(0), -(bz + 1)) >= r)
        ++bz;
    } else {
      while (bz >= 0 && std::ldexp(tiling_.tile_size(0), -bz) < r)
        --bz;
    }
    return bz;
  }
  int64_t band_of(const Place& p, int bz) const {
    return bz < 0 ? 0 : static_cast<int64_t>(tile_row(p, bz));
  }

  std::unique_ptr<PlaceSorter> level_sorter(int z) const {
    // Two levels are sorting at once: the one read and the one filled.
    return std::make_unique<PlaceSorter>(s_.output + ".scratch-zoom" + std::to_string(z),
                                         (s_.memory_mb << 20) / 2, fields_);
  }

  // One pass over a zoom's places (in sweep order), band by band: writes the
  // tiles of `write_zoom` and merges the places for `merge_zoom` into `out`.
  void sweep(PlaceSource& in, uint64_t count, std::optional<int> write_zoom,
             std::optional<int> merge_zoom, PlaceSorter* out, tileformat::PackageWriter& writer) {
    int bz = merge_zoom ? band_zoom(*merge_zoom) : *write_zoom;
    if (write_zoom) bz = std::min(bz, *write_zoom);  // bands hold whole tiles
    std::optional<BandMerger> merger;
    if (merge_zoom)
      merger.emplace(radius(*merge_zoom), wrap_, [&](const Place& p) { out->add(p); });
    std::optional<ZoomTiles> tiles;
    if (write_zoom) tiles.emplace(*this, *write_zoom, writer);
    progress_.begin(write_zoom ? "zoom " + std::to_string(*write_zoom) + " tiles"
                               : "aggregate zoom " + std::to_string(*merge_zoom),
                    count);
    std::vector<Place> band;
    int64_t current = 0;
    const auto flush = [&] {
      if (band.empty()) return;
      progress_.advance(band.size());
      if (tiles) tiles->add_band(band);
      if (merger) merger->add_band(current, std::move(band));
      band.clear();
    };
    Place p;
    while (in.next(p)) {
      const int64_t b = write_zoom && bz >= 0
                            ? int64_t(tile_row(p, *write_zoom) >> (*write_zoom - bz))
                            : band_of(p, bz);
      if (b != current) flush();
      current = b;
      band.push_back(std::move(p));
    }
    flush();
    if (merger) {
      merger->finish();
      sum_.peak_merge_places = std::max<uint64_t>(sum_.peak_merge_places, merger->peak_places());
    }
    if (tiles) tiles->finish();
    progress_.end();
  }

  // The tiles of one zoom, written band by band (tiles in key order within a
  // band), encoded in parallel batches.
  class ZoomTiles {
   public:
    ZoomTiles(Builder& b, int z, tileformat::PackageWriter& writer)
        : b_(b), z_(z), writer_(writer), stats_{z, 0, 0, 0} {
      reach_ = static_cast<uint32_t>(std::min<double>(
          b.s_.extent, std::ceil((b.s_.chart_max_px / 2 + 1) * b.s_.extent / kTilePx)));
    }

    void add_band(const std::vector<Place>& band) {
      const double ts = b_.tiling_.tile_size(z_), unit = ts / b_.s_.extent;
      const size_t first = items_.size();
      for (const Place& p : band) {
        const uint64_t tx = b_.tile_column(p, z_), ty = b_.tile_row(p, z_);
        const double ux = (p.x - (b_.tiling_.origin_x + double(tx) * ts)) / unit;
        const double uy = ((b_.tiling_.origin_y - double(ty) * ts) - p.y) / unit;
        const auto coord = [&](double u) {
          return static_cast<int32_t>(std::clamp<long long>(std::llround(u), 0, b_.s_.extent));
        };
        items_.push_back({tile_key({z_, uint32_t(tx), uint32_t(ty)}),
                          p.id,
                          p.count,
                          uint32_t(values_.size()),
                          {coord(ux), coord(uy)}});
        for (double v : p.sums)
          values_.push_back(b_.s_.aggregate == tileformat::PointAggregate::kSum ? v : v / p.count);
      }
      std::sort(items_.begin() + std::ptrdiff_t(first), items_.end(),
                [](const Item& a, const Item& b) {
                  return a.key != b.key ? a.key < b.key : a.id < b.id;
                });
      for (size_t k = first; k < items_.size();) {
        size_t end = k;
        while (end < items_.size() && items_[end].key == items_[k].key)
          ++end;
        tiles_.emplace_back(k, end);
        k = end;
      }
      stats_.places += band.size();
      if (items_.size() >= kBatchPlaces) flush();
    }

    void finish() {
      flush();
      b_.zooms_.insert(b_.zooms_.begin(), stats_);
    }

   private:
    // Points tiles hold few places: batches of this many keep both cores busy.
    static constexpr size_t kBatchPlaces = 1 << 16;
    struct Item {
      uint64_t key;     // tile_key of its tile
      uint64_t id;      // the place's id (order within a tile)
      uint32_t count;   // source places
      uint32_t values;  // its shown values in values_
      tileformat::PlacePosition at;
    };

    void flush() {
      const int fields = b_.fields_;
      parallel_batches<NoInputs, std::vector<uint8_t>>(
          tiles_.size(), b_.threads_, size_t(64 * b_.threads_),
          [](size_t, size_t) { return NoInputs{}; },
          [&](size_t t, int, const NoInputs&) {
            tileformat::PointTile tile;
            tile.extent = static_cast<uint32_t>(b_.s_.extent);
            tile.grid = static_cast<uint32_t>(b_.s_.cluster_grid);
            tile.reach = reach_;
            tile.fields = static_cast<uint32_t>(fields);
            for (size_t k = tiles_[t].first; k < tiles_[t].second; ++k) {
              const Item& it = items_[k];
              tile.places.push_back({it.id, it.count, it.at});
              for (int f = 0; f < fields; ++f)
                tile.values.push_back(static_cast<float>(values_[it.values + size_t(f)]));
            }
            tileformat::build_point_grid(tile);
            return tileformat::encode_point_tile(tile, kZstdLevel);
          },
          [&](size_t t, std::vector<uint8_t>&& blob) {
            for (size_t k = tiles_[t].first; k < tiles_[t].second; ++k) {
              double total = 0;
              for (int f = 0; f < fields; ++f) {
                const double shown = values_[items_[k].values + size_t(f)];
                total += std::abs(shown);
                stats_.max_value = std::max(stats_.max_value, std::abs(shown));
              }
              stats_.max_total = std::max(stats_.max_total, total);
            }
            if (b_.skip_ > 0)
              --b_.skip_;
            else
              writer_.put_tile(key_tile(items_[tiles_[t].first].key), blob);
          },
          [](size_t) {});
      items_.clear();
      values_.clear();
      tiles_.clear();
    }

    Builder& b_;
    const int z_;
    tileformat::PackageWriter& writer_;
    tileformat::PointZoomStats stats_;
    uint32_t reach_;
    std::vector<Item> items_;
    std::vector<double> values_;
    std::vector<std::pair<size_t, size_t>> tiles_;  // item ranges
  };

  tileformat::PointMetadata metadata() const {
    tileformat::PointMetadata m;
    m.common = vector_common_metadata(s_, "Points", tileformat::kPointsFormat, frame_, tiling_,
                                      extent_, area_, sum_.min_zoom, sum_.max_zoom);
    m.extent = s_.extent;
    m.cluster_grid = s_.cluster_grid;
    m.tile_px = kTilePx;
    m.chart_max_px = s_.chart_max_px;
    m.fields = s_.fields;
    m.aggregate = s_.aggregate;
    m.merge_px = s_.merge_px;
    m.signed_values = s_.sign == ValueSign::kSigned;
    m.label_field = s_.label_field;
    m.features = kept_;
    m.zooms = zooms_;
    return m;
  }

  const PointsSettings& s_;
  Progress& progress_;
  const int threads_;
  const int fields_;
  VectorFrame frame_;
  tileformat::Tiling tiling_;
  Bounds extent_{1e300, 1e300, -1e300, -1e300};  // the places, tiling CRS
  Bounds area_;
  Wrap wrap_;
  uint64_t kept_ = 0;  // ids given
  int64_t label_count_ = 0;
  uint64_t skip_ = 0;                              // tiles a resumed package already holds
  std::vector<tileformat::PointZoomStats> zooms_;  // min..max zoom
  PointsSummary sum_;
};

}  // namespace

PointsSummary build_points(const PointsSettings& settings, Progress& progress) {
  return Builder(settings, progress).run();
}

}  // namespace globe
