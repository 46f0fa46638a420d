// Flow by least-cost routing (`--flow-method carve`): no depression is
// filled; a search in order of height from where water leaves the data (the
// grid's edges and the cells next to no data) visits every cell, and each
// cell drains to the neighbour that first reached it. Water so runs down
// into a depression and out along the lowest way over its rim, as if a
// channel had been carved through the rim (GRASS r.watershed's A* search,
// "impact reduction"; Ehlschlaeger 1989, Metz et al. 2011). On flats the
// earliest-reached cells are the nearest to the way out, so flats drain
// along the order the search entered them.
//
// The search: the lowest height first, the earliest queued among equal
// heights; neighbours in the order S, N, W, E, NE, SW, SE, NW. A cell
// first drains to the worked neighbour that queued it; while it waits, a
// later worked neighbour takes it over where the descent to that one is
// steeper (so water on a plane runs straight down its slope, not along the
// search's front), or as steep and that one drains off the data where its
// receiver does not. A diagonal neighbour is left to the orthogonal
// neighbour between (not yet worked, higher than this cell) when the climb
// from that one to it is steeper (against D8's diagonal bias). A seed drains
// off the data until a lower worked neighbour finds it. Ground distances
// are the grid's true ones (FlowGrid::dx, dy per row). GRASS 8.2's
// r.watershed -s agrees on 99.9-100 % of its stream cells in a projected
// location (tests/flow_test.cpp).
//
// The data's window of the grid is held in memory (kCarveBytesPerCell a
// cell): the search is one global order, not cut into chunks. Wraps
// east-west where the window is the whole width of a wrapping grid.
// docs/analysis.md, "Flow methods".
#pragma once

#include <cstdint>
#include <vector>

#include "analysis/flow/flow_grid.hpp"
#include "tileformat/tile_id.hpp"

namespace globe::flow {

// Bytes a grid cell takes in a carve solve: heights 4, receiver and state 1,
// search order 4, then the queue's arrivals and links 8 or upstream areas 8,
// and the pyramid's finest level 9 (the synthetic 4096^2 DEM peaked at
// 475 MB, 28 bytes a cell with the process's own).
inline constexpr uint64_t kCarveBytesPerCell = 26;

// The cells the data lies in: columns x0 .. x0 + w - 1 (modulo the grid's
// width where it wraps), rows y0 .. y0 + h - 1.
struct GridWindow {
  int64_t x0 = 0, y0 = 0, w = 0, h = 0;
  bool wraps = false;  // the whole width of a wrapping grid: wraps itself
  // The bounding box of the finest tiles' cells; on a wrapping grid the
  // shortest run of tile columns that holds them all (data across the
  // antimeridian is one window).
  static GridWindow of_tiles(const FlowGrid& grid, const std::vector<tileformat::TileId>& finest);
  uint64_t cells() const { return uint64_t(w) * uint64_t(h); }
  // The window cell (row-major index) of grid cell (gx, gy), or -1.
  int64_t local(const FlowGrid& grid, int64_t gx, int64_t gy) const {
    if (gy < y0 || gy >= y0 + h) return -1;
    const int64_t lx = ((gx - x0) % grid.width() + grid.width()) % grid.width();
    return lx < w ? (gy - y0) * w + lx : -1;
  }
};

struct CarvedFlow {
  std::vector<uint8_t> code;   // per cell: D8 receiver code, kOutlet, kNoDataCode
  std::vector<uint64_t> area;  // per cell: upstream area units (0 where no data)
};

// `heights`: the window's cells, row-major (kNoData where none); the result
// is per window cell too. Throws std::length_error past 2^32 - 1 cells.
CarvedFlow route_least_cost(const FlowGrid& grid, const GridWindow& window,
                            const std::vector<int32_t>& heights);

}  // namespace globe::flow
