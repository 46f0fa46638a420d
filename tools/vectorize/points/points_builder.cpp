// Point package builder (see points_builder.hpp).
#include "points/points_builder.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <sstream>

#include "io/vector_frame.hpp"
#include "io/vector_reader.hpp"
#include "kit/package_output.hpp"
#include "kit/parallel_batches.hpp"
#include "lines/line_projector.hpp"
#include "points/point_aggregation.hpp"
#include "runtime/errors.hpp"
#include "tileformat/error.hpp"
#include "tileformat/feature_table.hpp"
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
        fields_(static_cast<int>(s.fields.size())),
        places_(fields_) {}

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
      read(reader, features);
      writer->checkpoint();
      tiling_ = frame_tiling(frame_, extent_);
      area_ = frame_area(frame_, tiling_, s_);
      keep_area();
      if (tiling_.wraps_x()) wrap_ = {tiling_.extent().width(), tiling_.extent().min_x};
      plan_zooms();
      skip_ = writer->resumed() ? writer->tiles_written() : 0;
      PlaceSet level = merge(places_, sum_.max_zoom);
      places_ = PlaceSet(fields_);  // the source places are not needed any more
      for (int z = sum_.max_zoom;; --z) {
        write_level(z, level, *writer);
        if (z == sum_.min_zoom) break;
        level = merge(level, z - 1);
      }
      sum_.coarsest_places = level.size();
    });
    writer->set_metadata(tileformat::to_metadata(metadata()));
    commit_package(*writer, s_.output, start, sum_);
    return sum_;
  }

 private:
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

  void read(VectorReader& reader, tileformat::FeatureTableWriter& features) {
    std::vector<LineProjector> projectors;
    for (const VectorLayerInfo& l : reader.layers())
      projectors.emplace_back(frame_.frame, *l.crs, frame_.target ? &*frame_.target : nullptr);
    int64_t total = 0;
    for (const VectorLayerInfo& l : reader.layers())
      total += std::max<int64_t>(0, l.feature_count);
    progress_.begin("read places", static_cast<uint64_t>(total));
    VectorFeature vf;
    std::vector<double> values(fields_);
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
        values[f] = v;
      }
      const uint64_t id = ++kept_;
      if (!features.complete())
        features.add(static_cast<int64_t>(id), layer.name, vf.properties_json);
      places_.add(at.x, at.y, id, 1, values);
      extent_ = {std::min(extent_.min_x, at.x), std::min(extent_.min_y, at.y),
                 std::max(extent_.max_x, at.x), std::max(extent_.max_y, at.y)};
    }
    progress_.end();
    if (places_.size() == 0) {
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
  // projected place).
  void keep_area() {
    PlaceSet kept(fields_);
    kept.reserve(places_.size());
    for (size_t i = 0; i < places_.size(); ++i) {
      if (places_.x(i) < area_.min_x || places_.x(i) > area_.max_x || places_.y(i) < area_.min_y ||
          places_.y(i) > area_.max_y) {
        ++sum_.skipped_outside;
        continue;
      }
      kept.add(places_.x(i), places_.y(i), places_.id(i), places_.count(i), places_.sums(i));
    }
    if (kept.size() == 0)
      throw InputError(s_.inputs[0] + ": no place falls in the requested area (check --bbox); " +
                       "nothing written");
    sum_.places = kept.size();
    places_ = std::move(kept);
  }

  double radius(int z) const { return s_.merge_px * tiling_.tile_size(z) / kTilePx; }

  void plan_zooms() {
    sum_.min_zoom = s_.min_zoom.value_or(0);
    if (s_.max_zoom) {
      sum_.max_zoom = *s_.max_zoom;
    } else {
      // The share of crowded places and the places per tile fall as the
      // zoom grows: bisect.
      int lo = sum_.min_zoom, hi = std::max(sum_.min_zoom, kDefaultMaxZoomCap);
      progress_.begin("choose the finest zoom", 0);
      while (lo < hi) {
        const int mid = (lo + hi) / 2;
        if (double(places_.size()) < kFewestPlacesPerTile * double(tiles_holding(mid)) ||
            crowded_share(places_, radius(mid), wrap_) <= kCrowdedShare)
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

  // How many tiles of zoom z the source places lie in.
  size_t tiles_holding(int z) const {
    const double ts = tiling_.tile_size(z);
    std::vector<uint64_t> keys(places_.size());
    for (size_t i = 0; i < places_.size(); ++i)
      keys[i] =
          tile_key({z, uint32_t(std::max(0.0, std::floor((places_.x(i) - tiling_.origin_x) / ts))),
                    uint32_t(std::max(0.0, std::floor((tiling_.origin_y - places_.y(i)) / ts)))});
    std::sort(keys.begin(), keys.end());
    return size_t(std::unique(keys.begin(), keys.end()) - keys.begin());
  }

  PlaceSet merge(const PlaceSet& in, int z) {
    progress_.begin("aggregate zoom " + std::to_string(z), 0);
    PlaceSet out = merge_places(in, radius(z), wrap_);
    progress_.end();
    return out;
  }

  struct Item {
    uint64_t key;    // tile_key of its tile
    uint64_t id;     // the place's id (order within a tile)
    uint32_t index;  // into the level
    tileformat::PlacePosition at;
  };

  void write_level(int z, const PlaceSet& level, tileformat::PackageWriter& writer) {
    const double ts = tiling_.tile_size(z), unit = ts / s_.extent;
    const double nx = double(tiling_.tiles_x(z)), ny = double(tiling_.tiles_y(z));
    std::vector<Item> items(level.size());
    for (uint32_t i = 0; i < level.size(); ++i) {
      const double tx = std::clamp(std::floor((level.x(i) - tiling_.origin_x) / ts), 0.0, nx - 1);
      const double ty = std::clamp(std::floor((tiling_.origin_y - level.y(i)) / ts), 0.0, ny - 1);
      const double ux = (level.x(i) - (tiling_.origin_x + tx * ts)) / unit;
      const double uy = ((tiling_.origin_y - ty * ts) - level.y(i)) / unit;
      const auto coord = [&](double u) {
        return static_cast<int32_t>(std::clamp<long long>(std::llround(u), 0, s_.extent));
      };
      items[i] = {
          tile_key({z, uint32_t(tx), uint32_t(ty)}), level.id(i), i, {coord(ux), coord(uy)}};
    }
    std::sort(items.begin(), items.end(), [](const Item& a, const Item& b) {
      return a.key != b.key ? a.key < b.key : a.id < b.id;
    });
    std::vector<std::pair<size_t, size_t>> tiles;  // item ranges
    for (size_t k = 0; k < items.size();) {
      size_t end = k;
      while (end < items.size() && items[end].key == items[k].key)
        ++end;
      tiles.emplace_back(k, end);
      k = end;
    }
    tileformat::PointZoomStats stats{z, level.size(), 0, 0};
    const uint32_t reach = static_cast<uint32_t>(
        std::min<double>(s_.extent, std::ceil((s_.chart_max_px / 2 + 1) * s_.extent / kTilePx)));
    progress_.begin("zoom " + std::to_string(z) + " tiles", tiles.size());
    parallel_batches<NoInputs, std::vector<uint8_t>>(
        tiles.size(), threads_, size_t(64 * threads_), [](size_t, size_t) { return NoInputs{}; },
        [&](size_t t, int, const NoInputs&) {
          tileformat::PointTile tile;
          tile.extent = static_cast<uint32_t>(s_.extent);
          tile.grid = static_cast<uint32_t>(s_.cluster_grid);
          tile.reach = reach;
          tile.fields = static_cast<uint32_t>(fields_);
          for (size_t k = tiles[t].first; k < tiles[t].second; ++k) {
            const Item& it = items[k];
            const uint32_t count = level.count(it.index);
            tile.places.push_back({it.id, count, it.at});
            for (double v : level.sums(it.index))
              tile.values.push_back(static_cast<float>(
                  s_.aggregate == tileformat::PointAggregate::kSum ? v : v / count));
          }
          tileformat::build_point_grid(tile);
          return tileformat::encode_point_tile(tile, kZstdLevel);
        },
        [&](size_t t, std::vector<uint8_t>&& blob) {
          for (size_t k = tiles[t].first; k < tiles[t].second; ++k) {
            double total = 0;
            for (double v : level.sums(items[k].index)) {
              const double shown = s_.aggregate == tileformat::PointAggregate::kSum
                                       ? v
                                       : v / level.count(items[k].index);
              total += std::abs(shown);
              stats.max_value = std::max(stats.max_value, std::abs(shown));
            }
            stats.max_total = std::max(stats.max_total, total);
          }
          if (skip_ > 0)
            --skip_;
          else
            writer.put_tile(key_tile(items[tiles[t].first].key), blob);
          progress_.advance();
        },
        [](size_t) {});
    progress_.end();
    zooms_.insert(zooms_.begin(), stats);
  }

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
  PlaceSet places_;
  uint64_t kept_ = 0;                              // ids given
  uint64_t skip_ = 0;                              // tiles a resumed package already holds
  std::vector<tileformat::PointZoomStats> zooms_;  // min..max zoom
  PointsSummary sum_;
};

}  // namespace

PointsSummary build_points(const PointsSettings& settings, Progress& progress) {
  return Builder(settings, progress).run();
}

}  // namespace globe
