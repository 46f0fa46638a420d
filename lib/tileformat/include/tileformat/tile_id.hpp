// Quadtree tile ids: (z, x, y) in XYZ order (y grows southwards from the top
// row), their parent/children, and the TMS row flip used by MBTiles storage.
// See docs/tileformat.md §2.
#pragma once

#include <array>
#include <compare>
#include <cstdint>
#include <string>

namespace tileformat {

inline constexpr int kMaxZoom = 30;

struct TileId {
  int z = 0;
  uint32_t x = 0;
  uint32_t y = 0;

  auto operator<=>(const TileId&) const = default;

  // Number of tiles along one axis of a root at this zoom.
  static uint64_t tiles_per_axis(int z) { return uint64_t{1} << z; }

  TileId parent() const { return {z - 1, x >> 1, y >> 1}; }  // precondition: z > 0
  std::array<TileId, 4> children() const {                   // order: (0,0) (1,0) (0,1) (1,1)
    return {TileId{z + 1, 2 * x, 2 * y}, TileId{z + 1, 2 * x + 1, 2 * y},
            TileId{z + 1, 2 * x, 2 * y + 1}, TileId{z + 1, 2 * x + 1, 2 * y + 1}};
  }
  // Position of this tile among its parent's children (index into children()).
  int child_index() const { return static_cast<int>((x & 1) + 2 * (y & 1)); }

  // MBTiles stores rows bottom-up: row = rows_at_zoom - 1 - y.
  static uint32_t flip_row(uint32_t row_or_y, uint64_t rows_at_zoom) {
    return static_cast<uint32_t>(rows_at_zoom - 1 - row_or_y);
  }

  // Orientation of the block's split diagonal: 0 = top-left to bottom-right,
  // 1 = top-right to bottom-left (docs/tileformat.md §6.1).
  int diagonal() const { return static_cast<int>((x + y) & 1); }

  std::string str() const {
    return std::to_string(z) + "/" + std::to_string(x) + "/" + std::to_string(y);
  }
};

}  // namespace tileformat
