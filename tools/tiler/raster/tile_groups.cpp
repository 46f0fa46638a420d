// Finest-zoom tiles and warp groups (see tile_groups.hpp).
#include "raster/tile_groups.hpp"

#include <algorithm>
#include <map>
#include <tuple>

namespace globe {

using tileformat::TileId;

void sort_tiles(std::vector<TileId>& v) {
  std::sort(v.begin(), v.end(),
            [](TileId a, TileId b) { return std::tie(a.y, a.x) < std::tie(b.y, b.x); });
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

std::vector<TileId> tiles_in_areas(const tileformat::Tiling& tiling,
                                   const std::vector<tileformat::Bounds>& areas, int z) {
  std::vector<TileId> out;
  for (const auto& area : areas) {
    auto r = tiling.tiles_covering(area, z);
    for (uint32_t y = r.min_y; !r.empty() && y <= r.max_y; ++y)
      for (uint32_t x = r.min_x; x <= r.max_x; ++x)
        out.push_back({z, x, y});
  }
  sort_tiles(out);
  return out;
}

std::vector<WarpGroup> group_tiles(const std::vector<TileId>& tiles, int g) {
  std::map<std::pair<uint32_t, uint32_t>, WarpGroup> by_key;  // (gy, gx): row-major order
  for (const TileId& t : tiles)
    by_key[{t.y / g, t.x / g}].members.push_back(t);
  std::vector<WarpGroup> groups;
  for (auto& [key, grp] : by_key) {
    uint32_t x0 = grp.members[0].x, x1 = x0, y0 = grp.members[0].y, y1 = y0;
    for (const TileId& t : grp.members) {
      x0 = std::min(x0, t.x);
      x1 = std::max(x1, t.x);
      y0 = std::min(y0, t.y);
      y1 = std::max(y1, t.y);
    }
    grp.first = {grp.members[0].z, x0, y0};
    grp.cols = static_cast<int>(x1 - x0 + 1);
    grp.rows = static_cast<int>(y1 - y0 + 1);
    groups.push_back(std::move(grp));
  }
  return groups;
}

}  // namespace globe
