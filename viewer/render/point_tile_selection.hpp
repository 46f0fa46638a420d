// Which point tiles a view draws charts from (docs/viewer.md "Charts"): a
// quadtree walk from the package's coarsest tiles that refines the tile
// covering the most pixels first, while it covers more than 1.5 x 256 pixels
// (a point tile is aggregated for 256 px per edge) and the package has finer
// tiles, within a tile budget. Tiles outside the view frustum, or on the
// globe behind the horizon, are dropped; only tiles the package holds are
// visited. The result comes back to front (farthest first), the order
// blended charts are drawn in.
#pragma once

#include <functional>
#include <vector>

#include "camera/camera.hpp"
#include "camera/layer_tiling.hpp"
#include "camera/world_frame.hpp"
#include "tileformat/tile_id.hpp"

namespace globe::viewer {

struct PointTileSelection {
  std::vector<tileformat::TileId> roots;  // the package's tiles at its coarsest zoom
  int max_zoom = 0;
  // Whether the package holds a tile (children are asked before a visit).
  std::function<bool(tileformat::TileId)> exists;
  double low_m = 0, high_m = 0;         // the terrain's height range (culling)
  const LayerTiling* tiling = nullptr;  // the package's tiles in the terrain's key units
  double refine_px = 1.5 * 256;         // a tile larger than this is refined
  size_t max_tiles = 4096;
};

std::vector<tileformat::TileId> select_point_tiles(const PointTileSelection& s, const View& view,
                                                   const WorldFrame& world);

// The selection with its broken tiles stood in for (issue 55): each by the
// children the package holds, or, where it has none (the finest zoom), by
// its parent, which then stands for its siblings too, so that no chart is
// drawn twice; again while a stand-in is known broken (a few rounds), and a
// tile with neither is left out. The order (back to front) is kept: a
// stand-in takes the place of the first tile it replaces.
std::vector<tileformat::TileId> stand_in_tiles(
    std::vector<tileformat::TileId> tiles, int min_zoom, int max_zoom,
    const std::function<bool(tileformat::TileId)>& exists,
    const std::function<bool(tileformat::TileId)>& broken);

}  // namespace globe::viewer
