// Point tile selection (see point_tile_selection.hpp).
#include "render/point_tile_selection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <set>

#include <glm/glm.hpp>

namespace globe::viewer {

using tileformat::TileId;

namespace {

// Tiles this coarse span too much of the globe for corner tests.
constexpr int kCullFromZoom = 3;

struct Measured {
  TileId id;
  double size_px = 0;   // largest projected extent (infinite across the eye plane)
  double distance = 0;  // eye to the tile's centre, world units
  bool visible = true;
};

Measured measure(TileId id, const View& view, const WorldFrame& world, const LayerTiling& tiling,
                 double low_m, double high_m) {
  Measured m{id};
  double lo_x = 1e300, lo_y = 1e300, hi_x = -1e300, hi_y = -1e300;
  bool behind = false, facing = false;
  std::array<int, 6> outside{};  // per frustum plane: samples outside it
  int samples = 0;
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 2; ++i) {
      const glm::dvec2 k = tiling.tile_to_key(id, i / 2.0, j / 2.0);
      const double kx = k.x, ky = k.y;
      const glm::dvec3 p = world.key_to_world(kx, ky, 0, view.origin);
      if (i == 1 && j == 1) m.distance = glm::length(p - view.eye);
      if (world.globe()) {
        const glm::dvec3 up = glm::normalize(world.key_to_world(kx, ky, 1000, view.origin) - p);
        facing = facing || glm::dot(up, view.eye - p) > 0;
      }
      for (double h : {low_m, high_m}) {
        const glm::dvec3 q = h == 0 ? p : world.key_to_world(kx, ky, h, view.origin);
        ++samples;
        for (int k = 0; k < 6; ++k)
          outside[k] += glm::dot(view.planes[k], glm::dvec4(q, 1)) < 0;
      }
      const glm::dvec4 c = view.proj * view.view * glm::dvec4(p, 1);
      if (c.w <= 1e-9) {
        behind = true;
        continue;
      }
      const double sx = (c.x / c.w * 0.5 + 0.5) * view.width,
                   sy = (c.y / c.w * 0.5 + 0.5) * view.height;
      lo_x = std::min(lo_x, sx), hi_x = std::max(hi_x, sx);
      lo_y = std::min(lo_y, sy), hi_y = std::max(hi_y, sy);
    }
  m.size_px = behind ? std::numeric_limits<double>::infinity() : std::max(hi_x - lo_x, hi_y - lo_y);
  if (id.z >= kCullFromZoom) {
    for (int k = 0; k < 6; ++k)
      if (outside[k] == samples) m.visible = false;
    if (world.globe() && !facing) m.visible = false;
  }
  return m;
}

}  // namespace

std::vector<TileId> select_point_tiles(const PointTileSelection& s, const View& view,
                                       const WorldFrame& world) {
  auto larger = [](const Measured& a, const Measured& b) {
    return a.size_px != b.size_px ? a.size_px < b.size_px : b.id < a.id;
  };
  std::priority_queue<Measured, std::vector<Measured>, decltype(larger)> open(larger);
  for (const TileId& r : s.roots) {
    const Measured m = measure(r, view, world, *s.tiling, s.low_m, s.high_m);
    if (m.visible) open.push(m);
  }
  std::vector<Measured> chosen;
  while (!open.empty()) {
    const Measured m = open.top();
    open.pop();
    std::vector<TileId> children;
    if (m.id.z < s.max_zoom && m.size_px > s.refine_px)
      for (const TileId& c : m.id.children())
        if (s.exists(c)) children.push_back(c);
    if (children.empty() || chosen.size() + open.size() + children.size() > s.max_tiles) {
      chosen.push_back(m);
      continue;
    }
    for (const TileId& c : children) {
      const Measured cm = measure(c, view, world, *s.tiling, s.low_m, s.high_m);
      if (cm.visible) open.push(cm);
    }
  }
  std::sort(chosen.begin(), chosen.end(), [](const Measured& a, const Measured& b) {
    return a.distance != b.distance ? a.distance > b.distance : a.id < b.id;
  });
  std::vector<TileId> out;
  for (const Measured& m : chosen)
    out.push_back(m.id);
  return out;
}

std::vector<TileId> stand_in_tiles(std::vector<TileId> tiles, int min_zoom, int max_zoom,
                                   const std::function<bool(TileId)>& exists,
                                   const std::function<bool(TileId)>& broken) {
  auto parent = [](const TileId& t) { return TileId{t.z - 1, t.x / 2, t.y / 2}; };
  for (int round = 0; round < 4; ++round) {
    bool changed = false;
    std::vector<TileId> out;
    std::set<TileId> parents;  // stand-ins for a broken child and its siblings
    for (const TileId& t : tiles) {
      if (!broken(t)) {
        out.push_back(t);
        continue;
      }
      changed = true;
      bool any = false;
      for (uint32_t c = 0; c < 4 && t.z < max_zoom; ++c) {
        const TileId child{t.z + 1, 2 * t.x + (c & 1), 2 * t.y + (c >> 1)};
        if (exists(child)) out.push_back(child), any = true;
      }
      if (!any && t.z > min_zoom) parents.insert(parent(t));
    }
    if (!parents.empty()) {
      std::vector<TileId> kept;
      std::set<TileId> placed;
      for (const TileId& t : out) {
        const bool covered = t.z > min_zoom && parents.count(parent(t));
        if (!covered) {
          kept.push_back(t);
        } else if (placed.insert(parent(t)).second) {
          kept.push_back(parent(t));
        }
      }
      for (const TileId& p : parents)  // a broken tile whose siblings were not selected
        if (placed.insert(p).second) kept.push_back(p);
      out = std::move(kept);
    }
    tiles = std::move(out);
    if (!changed) break;
  }
  std::erase_if(tiles, broken);
  return tiles;
}

}  // namespace globe::viewer
