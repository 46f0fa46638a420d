// The tiles a build warps at its finest zoom, and their grouping into blocks
// of up to g x g neighbours warped in one GDAL call (less per-call overhead).
// Groups depend only on tile positions, never on the thread count.
#pragma once

#include <vector>

#include "tileformat/tiling.hpp"

namespace globe {

struct WarpGroup {
  tileformat::TileId first;  // north-west corner of the block
  int cols = 1, rows = 1;
  std::vector<tileformat::TileId> members;  // in (y, x) order
};

// Tiles of zoom z intersecting any of `areas`, sorted by (y, x), unique.
std::vector<tileformat::TileId> tiles_in_areas(const tileformat::Tiling& tiling,
                                               const std::vector<tileformat::Bounds>& areas, int z);
// Sorts by (y, x) and removes duplicates.
void sort_tiles(std::vector<tileformat::TileId>& tiles);
// Groups tiles by aligned g x g blocks, in row-major block order.
std::vector<WarpGroup> group_tiles(const std::vector<tileformat::TileId>& tiles, int g);

}  // namespace globe
