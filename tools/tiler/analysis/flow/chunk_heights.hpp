// A chunk's heights with a ring of one cell around it, read from the terrain
// blocks of the finest zoom (quantized integers, kNoData where there is no
// data: holes, missing tiles, off the grid). Where blocks share an edge
// sample the block that owns it (the sample is not its east or south edge)
// wins; a neighbour's copy fills in where the owner has none.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "analysis/flow/flow_grid.hpp"
#include "analysis/height_window.hpp"

namespace globe::flow {

// Window cells: (w + 2) x (h + 2), x and y from -1 to w and h.
struct ChunkWindow {
  int w = 0, h = 0;
  explicit ChunkWindow(const Chunk& c) : w(c.w), h(c.h) {}
  size_t size() const { return size_t(w + 2) * (h + 2); }
  size_t at(int x, int y) const { return size_t(y + 1) * (w + 2) + size_t(x + 1); }
  int stride() const { return w + 2; }
  // The chunk's cells (w * h, row-major) into a window, and back out.
  template <typename T>
  void put_cells(const std::vector<T>& cells, std::vector<T>& window) const {
    for (int y = 0; y < h; ++y)
      std::copy_n(cells.begin() + ptrdiff_t(y) * w, w, window.begin() + ptrdiff_t(at(0, y)));
  }
  template <typename T>
  std::vector<T> take_cells(const std::vector<T>& window) const {
    std::vector<T> cells(size_t(w) * h);
    for (int y = 0; y < h; ++y)
      std::copy_n(window.begin() + ptrdiff_t(at(0, y)), w, cells.begin() + ptrdiff_t(y) * w);
    return cells;
  }
};

// The finest-zoom tiles whose samples the chunk's window reads.
std::vector<tileformat::TileId> chunk_tiles(const FlowGrid& grid, const Chunk& chunk);

std::vector<int32_t> chunk_heights(const FlowGrid& grid, const Chunk& chunk,
                                   const BlockLookup& block);

}  // namespace globe::flow
