// Line shards (see line_shard.hpp).
#include "shard/line_shard.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <unordered_map>

#include "tiles/tile_cutter.hpp"

namespace globe {

using tileformat::Bounds;
using tileformat::TileId;
using tileformat::TileRange;

namespace {

// Probing finer than this only grows the work table: 4^10 tiles give
// 16 subtrees per shard for 65,536 shards.
constexpr int kProbeZoomCap = 10;

// The first tile of zoom z inside `root` (z >= root.z).
TileId first_descendant(TileId root, int z) {
  return {z, root.x << (z - root.z), root.y << (z - root.z)};
}

TileId ancestor(TileId id, int z) {
  return {z, id.x >> (id.z - z), id.y >> (id.z - z)};
}

Bounds feature_bounds(const ProjectedFeature& f) {
  Bounds b{1e300, 1e300, -1e300, -1e300};
  auto extend = [&](XY p) {
    b = {std::min(b.min_x, p.x), std::min(b.min_y, p.y), std::max(b.max_x, p.x),
         std::max(b.max_y, p.y)};
  };
  for (const auto& part : f.lines)
    for (const XY& p : part)
      extend(p);
  for (const XY& p : f.points)
    extend(p);
  return b;
}

}  // namespace

LineShard::LineShard(const LinesSettings& s, const LinePlan& plan, GeometryScratch& scratch,
                     uint64_t features, Progress& progress)
    : lines_(plan) {
  // Work: the vertices in each tile of the probe zoom.
  const int probe =
      std::min(plan.max_zoom, std::max({kProbeZoomCap, plan.min_zoom, s.split_zoom.value_or(0)}));
  const tileformat::Tiling& t = plan.tiling;
  const double size = t.tile_size(probe);
  const double nx = double(t.tiles_x(probe)), ny = double(t.tiles_y(probe));
  std::unordered_map<uint64_t, uint64_t> vertices;  // tile_key -> vertices in it
  auto count = [&](XY p) {
    const Bounds& a = plan.area;
    if (!(p.x >= a.min_x && p.x <= a.max_x && p.y >= a.min_y && p.y <= a.max_y)) return;
    const double x = std::clamp(std::floor((p.x - t.origin_x) / size), 0.0, nx - 1);
    const double y = std::clamp(std::floor((t.origin_y - p.y) / size), 0.0, ny - 1);
    ++vertices[tile_key({probe, uint32_t(x), uint32_t(y)})];
  };
  progress.begin("plan shard: work", features);
  ProjectedFeature f;
  while (scratch.read(f)) {
    for (const auto& part : f.lines)
      for (const XY& p : part)
        count(p);
    for (const XY& p : f.points)
      count(p);
    progress.advance();
  }
  scratch.rewind();
  progress.end();
  std::vector<TileWork> work;
  work.reserve(vertices.size());
  for (const auto& [key, n] : vertices)
    work.push_back({key_tile(key), n});
  std::sort(work.begin(), work.end(),
            [](const TileWork& a, const TileWork& b) { return a.id < b.id; });
  const int split = plan_shard(work, plan.min_zoom, s.split_zoom, *s.shard).split_zoom;

  // The cutter widens a zoom's tile boxes by its reach plus two grid units;
  // one more unit of the finest zoom covers snapping and touching borders.
  const double slack = t.tile_size(plan.max_zoom) / double(s.extent);
  reach_crs_.assign(plan.max_zoom + 1, 0);
  for (int z = plan.max_zoom; z >= plan.min_zoom; --z) {
    reach_crs_[z] = (plan.reach[z] + 2) * t.tile_size(z) / double(s.extent) + slack;
    if (z >= split && z < plan.max_zoom) reach_crs_[z] = std::max(reach_crs_[z], reach_crs_[z + 1]);
  }

  // Every tile of the split and coarser zooms a feature may reach, also
  // where none of its vertices lie (a segment crossing it, a simplified
  // shortcut, a line's width): those hold tiles too, and some shard must
  // own them.
  plan_.split_zoom = split;
  std::set<TileId> tiles;
  progress.begin("plan shard: tiles", features);
  while (scratch.read(f)) {
    const Bounds b = feature_bounds(f);
    for (int z = plan.min_zoom; z <= split; ++z) {
      const TileRange r = reached(b, z);
      for (uint32_t y = r.min_y; !r.empty() && y <= r.max_y; ++y)
        for (uint32_t x = r.min_x; x <= r.max_x; ++x)
          tiles.insert({z, x, y});
    }
    progress.advance();
  }
  scratch.rewind();
  progress.end();
  // A subtree's work: its vertices at each of its zooms; a coarse tile's:
  // its vertices once.
  std::map<TileId, uint64_t> under;
  for (const TileWork& w : work)
    for (int z = plan.min_zoom; z <= split; ++z)
      under[ancestor(w.id, z)] += w.work;
  const uint64_t levels = uint64_t(plan.max_zoom - split + 1);
  std::vector<TileWork> roots, coarse;
  for (const TileId& id : tiles) {
    auto it = under.find(id);
    const uint64_t n = it == under.end() ? 0 : it->second;
    if (id.z == split)
      roots.push_back({first_descendant(id, probe), n * levels});
    else
      coarse.push_back({id, n});
  }
  plan_ = plan_shard(roots, plan.min_zoom, split, *s.shard, coarse);
  progress.note(shard_summary(plan_, *s.shard));
}

TileRange LineShard::reached(const Bounds& b, int z) const {
  if (b.min_x > b.max_x) return {};  // no vertex
  const double r = reach_crs_[z];
  return lines_.tiling.tiles_covering({b.min_x - r, b.min_y - r, b.max_x + r, b.max_y + r}, z);
}

bool LineShard::owns_any(const TileRange& r, int z) const {
  if (r.empty()) return false;
  const auto& all = plan_.roots;  // sorted by (z, x, y)
  const auto first = std::lower_bound(all.begin(), all.end(), TileId{z, 0, 0});
  const auto last = std::lower_bound(first, all.end(), TileId{z + 1, 0, 0});
  if (r.count() > uint64_t(last - first))
    return std::any_of(first, last, [&](const TileId& id) {
      return id.x >= r.min_x && id.x <= r.max_x && id.y >= r.min_y && id.y <= r.max_y;
    });
  for (uint32_t y = r.min_y; y <= r.max_y; ++y)
    for (uint32_t x = r.min_x; x <= r.max_x; ++x)
      if (std::binary_search(first, last, TileId{z, x, y})) return true;
  return false;
}

uint32_t LineShard::zooms_to_cut(const ProjectedFeature& f) const {
  const Bounds b = feature_bounds(f);
  uint32_t zooms = 0;
  for (int z = lines_.min_zoom; z < plan_.split_zoom; ++z)
    if (owns_any(reached(b, z), z)) zooms |= 1u << z;
  if (owns_any(reached(b, plan_.split_zoom), plan_.split_zoom))
    for (int z = plan_.split_zoom; z <= lines_.max_zoom; ++z)
      zooms |= 1u << z;
  return zooms;
}

}  // namespace globe
