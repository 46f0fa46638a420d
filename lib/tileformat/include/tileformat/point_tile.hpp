// Point tiles (docs/tileformat.md §11): the places of one quadtree tile, for
// drawing a chart at each. A place has a tile-local integer position (x east,
// y south, 0..extent across the tile), a stable id (a row of the package's
// features table: the place's own, or for an aggregate of several places the
// smallest of theirs), the number of source places it stands for, and one
// float32 value per field of the package. A C x C cluster grid in CSR form
// lists, per cell, every place within `reach` units of the cell (its chart
// may cover part of the cell), so a pixel finds the charts over it.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace tileformat {

struct PlacePosition {
  int32_t x = 0, y = 0;
  bool operator==(const PlacePosition&) const = default;
};

struct Place {
  uint64_t id = 0;     // features table id; strictly increasing within a tile
  uint32_t count = 1;  // source places it stands for (>= 1)
  PlacePosition at;    // tile-local units, 0..extent
};

struct PointTile {
  uint32_t extent = 4096;  // units per tile edge
  uint32_t grid = 16;      // cluster cells per side; extent % grid == 0
  uint32_t reach = 0;      // units: the largest chart's half size the grid was built for
  uint32_t fields = 0;     // values per place
  std::vector<Place> places;
  std::vector<float> values;           // places.size() * fields, place after place
  std::vector<uint32_t> cell_offsets;  // grid*grid + 1, row-major cells (y, then x)
  std::vector<uint32_t> cell_places;   // ascending place indices per cell

  float value(size_t place, uint32_t field) const { return values[place * fields + field]; }
  // Cell of a tile-local position (clamped into the grid).
  uint32_t cell_of(double x, double y) const;
};

// Counts readable from the uncompressed part of a blob (for `info`).
struct PointTileCounts {
  uint32_t places = 0, fields = 0, cell_entries = 0;
};

// Calls fn(cell) for every cell of `tile`'s grid within reach of `at`
// (§11.3), in ascending cell order.
template <typename Fn>
void for_each_cell_near(const PointTile& tile, PlacePosition at, Fn fn);

// Fills tile.cell_offsets / cell_places from its places, grid and reach.
void build_point_grid(PointTile& tile);

// Encodes `tile` (grid included) as a blob with header. Throws FormatError
// if the tile breaks the §11 invariants.
std::vector<uint8_t> encode_point_tile(const PointTile& tile, int zstd_level = 9);
// Decodes and checks every §11 invariant; throws FormatError.
PointTile decode_point_tile(std::span<const uint8_t> blob);
PointTileCounts peek_point_tile_counts(std::span<const uint8_t> blob);

template <typename Fn>
void for_each_cell_near(const PointTile& tile, PlacePosition at, Fn fn) {
  const int64_t g = tile.grid, s = tile.extent / tile.grid, r = tile.reach;
  // Cells whose closed square comes within r of the point: the candidate
  // range from the bounding box, then the exact distance to each.
  auto range = [&](int64_t v, int64_t& lo, int64_t& hi) {
    lo = (v - r) / s - 1;
    hi = (v + r) / s + 1;
    lo = lo < 0 ? 0 : lo;
    hi = hi > g - 1 ? g - 1 : hi;
  };
  int64_t x0, x1, y0, y1;
  range(at.x, x0, x1);
  range(at.y, y0, y1);
  for (int64_t cy = y0; cy <= y1; ++cy)
    for (int64_t cx = x0; cx <= x1; ++cx) {
      const int64_t dx =
          at.x < cx * s ? cx * s - at.x : (at.x > (cx + 1) * s ? at.x - (cx + 1) * s : 0);
      const int64_t dy =
          at.y < cy * s ? cy * s - at.y : (at.y > (cy + 1) * s ? at.y - (cy + 1) * s : 0);
      if (dx * dx + dy * dy <= r * r) fn(static_cast<uint32_t>(cy * g + cx));
    }
}

}  // namespace tileformat
