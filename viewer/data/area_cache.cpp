// Area tile cache (see area_cache.hpp).
#include "data/area_cache.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "tileformat/line_clusters.hpp"

namespace globe::viewer {

using tileformat::TileId;

namespace {

struct Edge {
  double ax, ay, bx, by;
};

uint32_t float_bits(double v) {
  return std::bit_cast<uint32_t>(static_cast<float>(v));
}

// Whether segment e meets the closed box [x0, x1] x [y0, y1] (Liang-Barsky,
// as the line clusters' grid rule).
bool meets_box(const Edge& e, double x0, double y0, double x1, double y1) {
  double t0 = 0, t1 = 1;
  return tileformat::clip_parameters(e.ax, e.ay, e.bx, e.by, x0, y0, x1, y1, t0, t1);
}

struct CellEntry {
  uint32_t polygon;
  int32_t winding;
  std::vector<uint32_t> edges;
};

// The winding number change from r to q across edge a-b: the fill pass's
// rule (area_shaders.hpp), in coordinates relative to r.
int crossing(double ax, double ay, double bx, double by, double qx, double qy) {
  auto cross = [](double ux, double uy, double vx, double vy) { return ux * vy - uy * vx; };
  const bool sa = cross(qx, qy, ax, ay) > 0, sb = cross(qx, qy, bx, by) > 0;
  if (sa == sb) return 0;
  const bool sr = cross(bx - ax, by - ay, -ax, -ay) > 0;
  const bool sq = cross(bx - ax, by - ay, qx - ax, qy - ay) > 0;
  if (sr == sq) return 0;
  return (sq ? 1 : 0) - (sr ? 1 : 0);
}

}  // namespace

DecodedAreaTile area_tile_words(const tileformat::AreaTile& t, uint32_t grid, double reach,
                                uint32_t world_sides) {
  DecodedAreaTile d;
  d.extent = t.extent;
  d.grid = grid;
  d.feature_ids = t.feature_ids;
  const double s = double(t.extent) / grid, extent = t.extent;
  const std::vector<uint32_t> offsets = t.ring_offsets();
  std::vector<Edge> edges;
  std::vector<std::vector<CellEntry>> cells(size_t{grid} * grid);
  std::vector<std::vector<std::pair<double, int>>> rows(grid);  // per row: crossing x, sign
  std::vector<std::pair<uint32_t, uint32_t>> touches;           // (cell, edge)
  std::vector<int32_t> winding(size_t{grid} * grid);
  for (uint32_t p = 0; p < t.polygons.size(); ++p) {
    const tileformat::AreaPolygon& poly = t.polygons[p];
    d.polygon_feature.push_back(poly.feature);
    for (auto& r : rows)
      r.clear();
    touches.clear();
    for (uint32_t r = poly.first_ring; r < poly.first_ring + poly.ring_count; ++r) {
      const uint32_t n = t.ring_sizes[r];
      for (uint32_t i = 0; i < n; ++i) {
        const tileformat::LineVertex a = t.vertices[offsets[r] + i],
                                     b = t.vertices[offsets[r] + (i + 1) % n];
        const Edge e{double(a.x), double(a.y), double(b.x), double(b.y)};
        // Crossings of the rows' reference lines (y never equals a vertex's).
        const double lo = std::min(e.ay, e.by), hi = std::max(e.ay, e.by);
        const int r0 = std::max(0, static_cast<int>(std::ceil((lo - kAreaRefY) / s)));
        const int r1 = std::min(int(grid) - 1, static_cast<int>(std::floor((hi - kAreaRefY) / s)));
        for (int row = r0; row <= r1; ++row) {
          const double y = row * s + kAreaRefY;
          if ((e.ay <= y) == (e.by <= y)) continue;
          rows[row].emplace_back(e.ax + (y - e.ay) * (e.bx - e.ax) / (e.by - e.ay),
                                 e.by > e.ay ? 1 : -1);
        }
        // The cells it touches (none for edges wholly in the buffer).
        if (std::max(e.ax, e.bx) < -reach || std::min(e.ax, e.bx) > extent + reach ||
            std::max(e.ay, e.by) < -reach || std::min(e.ay, e.by) > extent + reach)
          continue;
        const uint32_t edge = static_cast<uint32_t>(edges.size());
        edges.push_back(e);
        auto cell = [&](double v) {
          return std::clamp(static_cast<int>(std::floor(v / s)), 0, int(grid) - 1);
        };
        const int cx0 = cell(std::min(e.ax, e.bx) - reach),
                  cx1 = cell(std::max(e.ax, e.bx) + reach);
        const int cy0 = cell(std::min(e.ay, e.by) - reach),
                  cy1 = cell(std::max(e.ay, e.by) + reach);
        for (int cy = cy0; cy <= cy1; ++cy)
          for (int cx = cx0; cx <= cx1; ++cx)
            if (meets_box(e, cx * s - reach, cy * s - reach, (cx + 1) * s + reach,
                          (cy + 1) * s + reach))
              touches.emplace_back(uint32_t(cy) * grid + uint32_t(cx), edge);
      }
    }
    // Winding numbers at the reference points: the signed crossings right of them.
    for (uint32_t row = 0; row < grid; ++row) {
      auto& xs = rows[row];
      std::sort(xs.begin(), xs.end(),
                [](const auto& a, const auto& b) { return a.first > b.first; });
      int w = 0;
      size_t k = 0;
      for (int cx = int(grid) - 1; cx >= 0; --cx) {
        const double x = cx * s + kAreaRefX;
        for (; k < xs.size() && xs[k].first > x; ++k)
          w += xs[k].second;
        winding[size_t(row) * grid + size_t(cx)] = w;
      }
    }
    std::sort(touches.begin(), touches.end());
    size_t k = 0;
    for (uint32_t c = 0; c < grid * grid; ++c) {
      const size_t first = k;
      while (k < touches.size() && touches[k].first == c)
        ++k;
      if (winding[c] == 0 && k == first) continue;
      CellEntry entry{p, winding[c], {}};
      for (size_t i = first; i < k; ++i)
        entry.edges.push_back(touches[i].second);
      cells[c].push_back(std::move(entry));
    }
  }
  // The words.
  d.edges = static_cast<uint32_t>(edges.size());
  d.polygons = static_cast<uint32_t>(t.polygons.size());
  std::vector<uint32_t> cell_offsets(size_t{grid} * grid + 1, 0);
  for (size_t c = 0; c < cells.size(); ++c) {
    cell_offsets[c + 1] = cell_offsets[c] + static_cast<uint32_t>(cells[c].size());
    for (const CellEntry& e : cells[c])
      d.edge_refs += static_cast<uint32_t>(e.edges.size());
  }
  d.entries = cell_offsets.back();
  d.words = cell_offsets;
  uint32_t ref = 0;
  for (const auto& c : cells)
    for (const CellEntry& e : c) {
      d.words.insert(d.words.end(), {e.polygon, std::bit_cast<uint32_t>(e.winding), ref,
                                     static_cast<uint32_t>(e.edges.size())});
      ref += static_cast<uint32_t>(e.edges.size());
    }
  for (const auto& c : cells)
    for (const CellEntry& e : c)
      d.words.insert(d.words.end(), e.edges.begin(), e.edges.end());
  auto cut = [&](const Edge& e) {
    return tileformat::along_map_edge(world_sides, e.ax, e.ay, e.bx, e.by, extent);
  };

  for (const Edge& e : edges)
    d.words.insert(d.words.end(), {float_bits(e.ax), float_bits(e.ay), float_bits(e.bx),
                                   float_bits(e.by), cut(e) ? 1u : 0u});
  for (const tileformat::AreaPolygon& p : t.polygons)
    d.words.insert(d.words.end(), {p.class_id, p.feature});
  return d;
}

int area_words_winding(const DecodedAreaTile& d, uint32_t polygon, double x, double y) {
  const double s = double(d.extent) / d.grid;
  const uint32_t cx = std::min(d.grid - 1, static_cast<uint32_t>(std::max(0.0, x / s)));
  const uint32_t cy = std::min(d.grid - 1, static_cast<uint32_t>(std::max(0.0, y / s)));
  const uint32_t c = cy * d.grid + cx;
  const double rx = cx * s + kAreaRefX, ry = cy * s + kAreaRefY;
  for (uint32_t k = d.words[c]; k < d.words[c + 1]; ++k) {
    const uint32_t* e = &d.words[d.entries_at() + k * kAreaEntryWords];
    if (e[0] != polygon) continue;
    int w = std::bit_cast<int32_t>(e[1]);
    for (uint32_t i = 0; i < e[3]; ++i) {
      const uint32_t edge = d.words[d.edge_refs_at() + e[2] + i];
      const uint32_t* g = &d.words[d.edges_at() + edge * kAreaEdgeWords];
      auto f = [&](uint32_t v) { return double(std::bit_cast<float>(v)); };
      w += crossing(f(g[0]) - rx, f(g[1]) - ry, f(g[2]) - rx, f(g[3]) - ry, x - rx, y - ry);
    }
    return w;
  }
  return 0;
}

namespace {

ArenaCacheSource area_source(const std::string& path, const AreaPackage& p) {
  return {path,
          p.reader.get(),
          p.meta.common.tiling,
          p.meta.common.min_zoom,
          p.meta.common.max_zoom,
          "area tile",
          "the areas of its coarser or finer tiles are drawn there",
          "--cache-mb"};
}

}  // namespace

AreaCache::AreaCache(const std::string& path, AreaPackage package, uint64_t budget_bytes)
    : ArenaTileCache(
          area_source(path, package), budget_bytes,
          [tiling = package.meta.common.tiling](TileId id, std::span<const uint8_t> blob) {
            return area_tile_words(tileformat::decode_area_tile(blob), 32, 24,
                                   tileformat::map_edge_sides(tiling, id));
          }),
      package_(std::move(package)) {}

AreaCache::~AreaCache() {
  stop_loader();
}

}  // namespace globe::viewer
