// Line tile passes (see line_tiles.hpp).
#include "lines/line_tiles.hpp"

#include "kit/parallel_batches.hpp"
#include "tileformat/line_clusters.hpp"
#include "tileformat/line_tile.hpp"
#include "tiles/tile_encoding.hpp"

namespace globe {

using tileformat::TileId;

void cut_line_tiles(GeometryScratch& scratch, uint64_t features, const LinePlan& plan,
                    const LineTileOptions& o, TileSorter& sorter, LineTileStats& stats,
                    Progress& progress) {
  const TileCutter cutter(plan.tiling, o.extent, o.simplify_px, plan.area);
  struct Result {
    std::vector<Emission> emissions;
    CutStats stats;
  };
  progress.begin("cut into tiles", features);
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
        batch.size(), o.threads, batch.size(), [](size_t, size_t) { return NoInputs{}; },
        [&](size_t i, int, const NoInputs&) {
          Result r;
          uint32_t sub = 0;  // only the order within one tile matters
          const uint32_t zooms = batch[i].zooms & (o.zooms ? o.zooms(batch[i]) : ~0u);
          for (int z = plan.min_zoom; z <= plan.max_zoom; ++z)
            if (zooms >> z & 1)
              cutter.cut(batch[i], z, plan.reach[z],
                         z == plan.max_zoom ? Collapsed::kKeep : Collapsed::kDrop, sub, r.emissions,
                         r.stats);
          if (o.keeps)
            std::erase_if(r.emissions,
                          [&](const Emission& e) { return !o.keeps(key_tile(e.key)); });
          return r;
        },
        [&](size_t i, Result&& r) {
          for (const Emission& e : r.emissions)
            sorter.add(e.key, batch[i].id, e.sub, e.piece.to_bytes());
          stats.cut.runs += r.stats.runs;
          stats.cut.collapsed_runs += r.stats.collapsed_runs;
          progress.advance();
        },
        [](size_t) {});
  }
  progress.end();
  sorter.finish();
}

namespace {

std::vector<uint8_t> encode_tile(const TileGroup& group, const LinePlan& plan,
                                 const LineTileOptions& o, uint64_t& segments, uint64_t& points) {
  const TileId id = key_tile(group.key);
  tileformat::LineTile t;
  t.extent = static_cast<uint32_t>(o.extent);
  t.grid = static_cast<uint32_t>(o.cluster_grid);
  t.reach = plan.reach[id.z];
  for (const TileRecord& rec : group.records) {
    if (t.feature_ids.empty() || t.feature_ids.back() != rec.seq) t.feature_ids.push_back(rec.seq);
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

}  // namespace

void encode_line_tiles(TileSorter& sorter, const LinePlan& plan, const LineTileOptions& o,
                       tileformat::PackageWriter& writer, LineTileStats& stats,
                       Progress& progress) {
  encode_sorted_tiles(
      sorter, o.threads, writer, progress,
      [&](const TileGroup& g) {
        EncodedTile e;
        e.blob = encode_tile(g, plan, o, e.first, e.second);
        return e;
      },
      [&](TileId id, const EncodedTile& e) {
        stats.segments += e.first;
        stats.points += e.second;
        if (id.z == plan.max_zoom) stats.max_zoom_segments += e.first;
      });
}

}  // namespace globe
