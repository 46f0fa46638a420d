// Cutting features into tiles (see tile_cutter.hpp).
#include "tiles/tile_cutter.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "tileformat/byte_io.hpp"

namespace globe {

using tileformat::LineVertex;
using tileformat::TileId;

std::vector<uint8_t> TilePiece::to_bytes() const {
  tileformat::ByteWriter w;
  w.u8(point ? 1 : 0);
  w.u32(class_id);
  w.u32(static_cast<uint32_t>(vertices.size()));
  for (const LineVertex& v : vertices) {
    w.i32(v.x);
    w.i32(v.y);
  }
  return w.take();
}

TilePiece TilePiece::from_bytes(std::span<const uint8_t> bytes) {
  tileformat::ByteReader r(bytes, "scratch tile piece", "7");
  TilePiece p;
  p.point = r.u8() != 0;
  p.class_id = r.u32();
  p.vertices.resize(r.u32());
  for (LineVertex& v : p.vertices) {
    v.x = r.i32();
    v.y = r.i32();
  }
  r.expect_end();
  return p;
}

uint64_t tile_key(TileId id) {
  return uint64_t(id.z) << 58 | uint64_t(id.y) << 29 | id.x;
}

TileId key_tile(uint64_t key) {
  constexpr uint64_t mask = (uint64_t{1} << 29) - 1;
  return {static_cast<int>(key >> 58), static_cast<uint32_t>(key & mask),
          static_cast<uint32_t>((key >> 29) & mask)};
}

TileCutter::TileCutter(const tileformat::Tiling& tiling, int extent, double simplify_px,
                       const tileformat::Bounds& area)
    : tiling_(tiling), extent_(extent), simplify_px_(simplify_px), area_(area) {}

void TileCutter::cut(const ProjectedFeature& f, int z, double reach_units, Collapsed collapsed,
                     uint32_t& sub, std::vector<Emission>& out, CutStats& stats) const {
  for (const auto& part : f.lines)
    cut_part(part, f.class_id, z, reach_units, collapsed, sub, out, stats);
  const double ts = tiling_.tile_size(z);
  const double unit = ts / extent_;
  for (const XY& p : f.points) {
    if (p.x < area_.min_x || p.x > area_.max_x || p.y < area_.min_y || p.y > area_.max_y) continue;
    const int64_t gx = std::llround((p.x - tiling_.origin_x) / unit);
    const int64_t gy = std::llround((tiling_.origin_y - p.y) / unit);
    const int64_t tx = std::clamp<int64_t>(gx / extent_, 0, int64_t(tiling_.tiles_x(z)) - 1);
    const int64_t ty = std::clamp<int64_t>(gy / extent_, 0, int64_t(tiling_.tiles_y(z)) - 1);
    TilePiece piece{
        true,
        f.class_id,
        {{static_cast<int32_t>(gx - tx * extent_), static_cast<int32_t>(gy - ty * extent_)}}};
    out.push_back({tile_key({z, uint32_t(tx), uint32_t(ty)}), sub++, std::move(piece)});
    ++stats.points;
  }
}

void TileCutter::cut_part(std::span<const XY> part, uint32_t class_id, int z, double reach_units,
                          Collapsed collapsed, uint32_t& sub, std::vector<Emission>& out,
                          CutStats& stats) const {
  const double ts = tiling_.tile_size(z);
  const double unit = ts / extent_;
  const double buf = (reach_units + 2) * unit;
  const int64_t nx = int64_t(tiling_.tiles_x(z)), ny = int64_t(tiling_.tiles_y(z));
  const double ox = tiling_.origin_x, oy = tiling_.origin_y;
  const std::vector<XY> s = douglas_peucker(part, simplify_px_ * ts / 256);

  struct Open {
    uint32_t sub;
    size_t last_segment;
    bool open_end;  // the last segment reached its input end unclipped
    TilePiece piece;
  };
  std::map<uint64_t, Open> open;
  auto flush = [&](uint64_t key, Open& o) {
    if (o.piece.vertices.size() == 1 && collapsed == Collapsed::kKeep)
      o.piece.vertices.push_back(o.piece.vertices[0]);
    if (o.piece.vertices.size() >= 2) {
      ++stats.runs;
      stats.segments += o.piece.vertices.size() - 1;
      out.push_back({key, o.sub, std::move(o.piece)});
    } else {
      ++stats.collapsed_runs;
    }
  };
  auto snap = [&](XY p, int64_t tx, int64_t ty) {
    const int64_t gx = std::llround((p.x - ox) / unit);
    const int64_t gy = std::llround((oy - p.y) / unit);
    return LineVertex{static_cast<int32_t>(gx - tx * extent_),
                      static_cast<int32_t>(gy - ty * extent_)};
  };
  auto cell = [&](double v, int64_t n) {
    return static_cast<int64_t>(std::clamp(std::floor(v / ts), 0.0, double(n - 1)));
  };

  for (size_t i = 0; i + 1 < s.size(); ++i) {
    XY a = s[i], b = s[i + 1];
    double ta0 = 0, ta1 = 1;
    if (!clip_segment(a, b, area_, &ta0, &ta1)) continue;
    const int64_t ty0 = cell(oy - std::max(a.y, b.y) - buf, ny);
    const int64_t ty1 = cell(oy - std::min(a.y, b.y) + buf, ny);
    for (int64_t ty = ty0; ty <= ty1; ++ty) {
      // Columns: where the segment runs within this row's (widened) band.
      XY c = a, d = b;
      const tileformat::Bounds band{-1e300, oy - (ty + 1) * ts - buf, 1e300, oy - ty * ts + buf};
      if (!clip_segment(c, d, band)) continue;
      const int64_t tx0 = cell(std::min(c.x, d.x) - buf - ox, nx);
      const int64_t tx1 = cell(std::max(c.x, d.x) + buf - ox, nx);
      for (int64_t tx = tx0; tx <= tx1; ++tx) {
        const TileId id{z, uint32_t(tx), uint32_t(ty)};
        tileformat::Bounds box = tiling_.tile_bounds(id);
        box = {box.min_x - buf, box.min_y - buf, box.max_x + buf, box.max_y + buf};
        XY p = a, q = b;
        double t0 = 0, t1 = 1;
        if (!clip_segment(p, q, box, &t0, &t1)) continue;
        const bool starts_at_vertex = ta0 == 0 && t0 == 0;
        const bool ends_at_vertex = ta1 == 1 && t1 == 1;
        const uint64_t key = tile_key(id);
        const LineVertex vp = snap(p, tx, ty), vq = snap(q, tx, ty);
        auto it = open.find(key);
        if (it != open.end() && it->second.open_end && starts_at_vertex &&
            it->second.last_segment + 1 == i) {
          if (!(it->second.piece.vertices.back() == vq)) it->second.piece.vertices.push_back(vq);
        } else {
          if (it != open.end()) {
            flush(key, it->second);
            open.erase(it);
          }
          Open o{sub++, i, false, TilePiece{false, class_id, {vp}}};
          if (!(vp == vq)) o.piece.vertices.push_back(vq);
          it = open.emplace(key, std::move(o)).first;
        }
        it->second.last_segment = i;
        it->second.open_end = ends_at_vertex;
      }
    }
  }
  for (auto& [key, o] : open)
    flush(key, o);
}

}  // namespace globe
