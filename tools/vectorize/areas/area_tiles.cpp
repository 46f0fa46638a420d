// Area tile passes (see area_tiles.hpp).
#include "areas/area_tiles.hpp"

#include <algorithm>
#include <cmath>

#include "areas/area_geometry.hpp"
#include "kit/parallel_batches.hpp"
#include "tileformat/area_tile.hpp"
#include "tileformat/byte_io.hpp"
#include "tiles/tile_cutter.hpp"
#include "tiles/tile_encoding.hpp"

namespace globe {

using tileformat::TileId;

void AreaScratch::write(const AreaFeature& f) {
  tileformat::ByteWriter w;
  w.u64(f.id);
  w.u32(f.class_id);
  w.u32(static_cast<uint32_t>(f.polygons.size()));
  for (const PlanePolygon& p : f.polygons) {
    w.u32(static_cast<uint32_t>(p.size()));
    for (const PlaneRing& r : p) {
      w.u32(static_cast<uint32_t>(r.size()));
      for (const PlanePoint& q : r) {
        w.f64(q.x);
        w.f64(q.y);
      }
    }
  }
  file_.append(w.take());
}

bool AreaScratch::read(AreaFeature& f) {
  if (!file_.next(buffer_)) return false;
  tileformat::ByteReader r(buffer_, file_.path() + ": scratch feature", "scratch");
  f.id = r.u64();
  f.class_id = r.u32();
  f.polygons.resize(r.u32());
  for (PlanePolygon& p : f.polygons) {
    p.resize(r.u32());
    for (PlaneRing& ring : p) {
      ring.resize(r.u32());
      for (PlanePoint& q : ring) {
        q.x = r.f64();
        q.y = r.f64();
      }
    }
  }
  r.expect_end();
  return true;
}

double area_snap_step(const AreaTileOptions& o, int z) {
  if (z == o.max_zoom) return 1;
  return std::max(1.0, std::round(o.extent / 256.0 * o.simplify_px));
}

namespace {

// A tile piece: one polygon's rings in tile units.
struct AreaPiece {
  uint32_t class_id = 0;
  std::vector<std::vector<tileformat::LineVertex>> rings;

  std::vector<uint8_t> to_bytes() const {
    tileformat::ByteWriter w;
    w.varint(class_id);
    w.varint(rings.size());
    for (const auto& r : rings) {
      w.varint(r.size());
      for (const auto& v : r) {
        w.svarint(v.x);
        w.svarint(v.y);
      }
    }
    return w.take();
  }
  static AreaPiece from_bytes(std::span<const uint8_t> b) {
    tileformat::ByteReader r(b, "area piece", "scratch");
    AreaPiece p;
    p.class_id = static_cast<uint32_t>(r.varint());
    p.rings.resize(r.varint());
    for (auto& ring : p.rings) {
      ring.resize(r.varint());
      for (auto& v : ring) {
        v.x = static_cast<int32_t>(r.svarint());
        v.y = static_cast<int32_t>(r.svarint());
      }
    }
    return p;
  }
};

struct AreaEmission {
  uint64_t key;
  uint32_t sub;
  std::vector<uint8_t> piece;
};

struct Box {
  double x0, y0, x1, y1;
};

Box bounds_of(const PlaneMultiPolygon& m) {
  Box b{1e300, 1e300, -1e300, -1e300};
  for (const PlanePolygon& p : m)
    for (const PlanePoint& q : p.front())
      b = {std::min(b.x0, q.x), std::min(b.y0, q.y), std::max(b.x1, q.x), std::max(b.y1, q.y)};
  return b;
}

// Integer tile units, repeats and dead rings removed, oriented; a piece
// GEOS finds invalid after rounding is repaired (counted).
PlaneMultiPolygon round_valid(PlaneMultiPolygon m, Geos& geos, uint64_t& repaired) {
  for (int pass = 0; pass < 3; ++pass) {
    uint64_t dropped = 0;
    m = snap_polygons(m, 1, false, dropped);
    if (m.empty() || geos.is_valid(m)) return m;
    ++repaired;
    m = geos.make_valid(m);
  }
  return m;
}

class AreaCutter {
 public:
  explicit AreaCutter(const AreaTileOptions& o) : o_(o) {}

  void cut(const AreaFeature& f, int z, Geos& geos, uint32_t& sub, std::vector<AreaEmission>& out,
           AreaTileStats& stats) const {
    const double step = area_snap_step(o_, z);
    PlaneMultiPolygon grid = snap_polygons(to_zoom_grid(f.polygons, o_.tiling, z, o_.extent), step,
                                           z == o_.max_zoom, stats.dropped_small);
    if (grid.empty()) return;
    if (!geos.is_valid(grid)) {
      ++stats.resnapped;
      grid = round_valid(geos.make_valid(grid), geos, stats.resnapped);
    }
    const double e = o_.extent, b = o_.buffer;
    const Box all = bounds_of(grid);
    // The tiles reached, within the area kept.
    const tileformat::TileRange keep = o_.tiling.tiles_covering(o_.area, z);
    if (keep.empty()) return;
    const auto tx0 = std::max<int64_t>(keep.min_x, int64_t(std::floor((all.x0 - b) / e)));
    const auto tx1 = std::min<int64_t>(keep.max_x, int64_t(std::floor((all.x1 + b) / e)));
    const auto ty0 = std::max<int64_t>(keep.min_y, int64_t(std::floor((all.y0 - b) / e)));
    const auto ty1 = std::min<int64_t>(keep.max_y, int64_t(std::floor((all.y1 + b) / e)));
    // Row strips, then the tiles of each (GEOS's rectangle clipping, each
    // geometry converted once per strip set). The boxes' edges lie half a
    // unit inside the buffer, where no vertex of the grid lies: GEOS's
    // rectangle clipping may turn a ring inside out when vertices lie on the
    // rectangle's edge; the points it adds there round back onto the
    // buffer's edge.
    const double h = b > 0 ? b - 0.5 : 0.0;
    std::vector<Geos::Box> strips;
    for (int64_t ty = ty0; ty <= ty1; ++ty)
      strips.push_back({all.x0 - 1, ty * e - h, all.x1 + 1, (ty + 1) * e + h});
    const bool one_row = ty0 == ty1 && all.y0 >= strips[0].y0 && all.y1 <= strips[0].y1;
    const std::vector<PlaneMultiPolygon> rows =
        one_row ? std::vector<PlaneMultiPolygon>{grid} : geos.clip_to_boxes(grid, strips);
    for (int64_t ty = ty0; ty <= ty1; ++ty) {
      const PlaneMultiPolygon& row = rows[size_t(ty - ty0)];
      if (row.empty()) continue;
      const double y0 = ty * e - h, y1 = (ty + 1) * e + h;
      const bool inside =
          one_row && tx0 == tx1 && all.x0 >= tx0 * e - h && all.x1 <= (tx0 + 1) * e + h;
      std::vector<Geos::Box> boxes;
      for (int64_t tx = tx0; tx <= tx1; ++tx)
        boxes.push_back({tx * e - h, y0, (tx + 1) * e + h, y1});
      std::vector<PlaneMultiPolygon> pieces =
          inside ? std::vector<PlaneMultiPolygon>{row} : geos.clip_to_boxes(row, boxes);
      for (int64_t tx = tx0; tx <= tx1; ++tx) {
        PlaneMultiPolygon& piece = pieces[size_t(tx - tx0)];
        if (piece.empty()) continue;
        if (!inside) piece = round_valid(std::move(piece), geos, stats.resnapped);
        for (const PlanePolygon& p : piece) {
          AreaPiece a;
          a.class_id = o_.class_of ? o_.class_of(f.id) : f.class_id;
          for (const PlaneRing& r : p) {
            a.rings.emplace_back();
            for (const PlanePoint& q : r)
              a.rings.back().push_back({static_cast<int32_t>(std::lround(q.x - tx * e)),
                                        static_cast<int32_t>(std::lround(q.y - ty * e))});
          }
          out.push_back({tile_key({z, uint32_t(tx), uint32_t(ty)}), sub++, a.to_bytes()});
        }
      }
    }
  }

 private:
  const AreaTileOptions& o_;
};

}  // namespace

void cut_area_tiles(AreaScratch& scratch, uint64_t features, const AreaTileOptions& o,
                    TileSorter& sorter, AreaTileStats& stats, Progress& progress) {
  const AreaCutter cutter(o);
  std::vector<std::unique_ptr<Geos>> geos;
  for (int i = 0; i < std::max(1, o.threads); ++i)
    geos.push_back(std::make_unique<Geos>());
  struct Result {
    std::vector<AreaEmission> emissions;
    AreaTileStats stats;
  };
  progress.begin("cut into tiles", features);
  std::vector<AreaFeature> batch;
  for (bool more = true; more;) {
    batch.clear();
    size_t vertices = 0;
    while (batch.size() < 1024 && vertices < (1u << 20)) {
      AreaFeature f;
      if (!scratch.read(f)) {
        more = false;
        break;
      }
      for (const PlanePolygon& p : f.polygons)
        for (const PlaneRing& r : p)
          vertices += r.size();
      batch.push_back(std::move(f));
    }
    parallel_batches<NoInputs, Result>(
        batch.size(), o.threads, batch.size(), [](size_t, size_t) { return NoInputs{}; },
        [&](size_t i, int worker, const NoInputs&) {
          Result r;
          uint32_t sub = 0;
          const uint32_t zooms = o.zooms ? o.zooms(batch[i]) : ~0u;
          for (int z = o.min_zoom; z <= o.max_zoom; ++z)
            if (zooms >> z & 1) cutter.cut(batch[i], z, *geos[worker], sub, r.emissions, r.stats);
          if (o.keeps)
            std::erase_if(r.emissions,
                          [&](const AreaEmission& e) { return !o.keeps(key_tile(e.key)); });
          return r;
        },
        [&](size_t i, Result&& r) {
          for (const AreaEmission& e : r.emissions)
            sorter.add(e.key, batch[i].id, e.sub, e.piece);
          stats.dropped_small += r.stats.dropped_small;
          stats.resnapped += r.stats.resnapped;
          progress.advance();
        },
        [](size_t) {});
  }
  progress.end();
  sorter.finish();
}

namespace {

std::vector<uint8_t> encode_tile(const TileGroup& group, const AreaTileOptions& o,
                                 uint64_t& polygons, uint64_t& vertices) {
  tileformat::AreaTile t;
  t.extent = static_cast<uint32_t>(o.extent);
  t.buffer = static_cast<uint32_t>(o.buffer);
  for (const TileRecord& rec : group.records) {
    if (t.feature_ids.empty() || t.feature_ids.back() != rec.seq) t.feature_ids.push_back(rec.seq);
    const AreaPiece piece = AreaPiece::from_bytes(group.payload(rec));
    t.polygons.push_back({static_cast<uint32_t>(t.feature_ids.size() - 1), piece.class_id,
                          static_cast<uint32_t>(t.ring_sizes.size()),
                          static_cast<uint32_t>(piece.rings.size())});
    for (const auto& r : piece.rings) {
      t.ring_sizes.push_back(static_cast<uint32_t>(r.size()));
      t.vertices.insert(t.vertices.end(), r.begin(), r.end());
    }
  }
  polygons = t.polygons.size();
  vertices = t.vertices.size();
  return tileformat::encode_area_tile(t);
}

}  // namespace

void encode_area_tiles(TileSorter& sorter, const AreaTileOptions& o,
                       tileformat::PackageWriter& writer, AreaTileStats& stats,
                       Progress& progress) {
  encode_sorted_tiles(
      sorter, o.threads, writer, progress,
      [&](const TileGroup& g) {
        EncodedTile e;
        e.blob = encode_tile(g, o, e.first, e.second);
        return e;
      },
      [&](TileId id, const EncodedTile& e) {
        stats.polygons += e.first;
        stats.vertices += e.second;
        if (id.z == o.max_zoom) stats.max_zoom_vertices += e.second;
      });
}

}  // namespace globe
