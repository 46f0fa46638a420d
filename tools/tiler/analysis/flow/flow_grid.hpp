// The finest zoom of a terrain package as one grid of cells for the flow
// solver (cell = sample; blocks share their edge samples, so a zoom with
// T tiles across has T * steps + 1 columns, or T * steps where the tiling
// wraps east-west), cut into square chunks of C cells a side, the unit of
// out-of-core work. Chunk origins are multiples of C; the last chunk column
// and row also take the grid's last column and row. Only chunks that touch
// a tile of the finest zoom exist. D8 codes, cell areas and ground spacing
// per row. Pure geometry, no I/O (docs/analysis.md, "Flow").
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "tileformat/tile_id.hpp"
#include "tileformat/tiling.hpp"

namespace globe::flow {

// D8 receiver codes: 0 none (an outlet: drains off the data), 1..8 the
// neighbour north, north-east, east .. north-west; kNoDataCode: no cell.
inline constexpr uint8_t kOutlet = 0, kNoDataCode = 9;
inline constexpr int kDx[9] = {0, 0, 1, 1, 1, 0, -1, -1, -1};
inline constexpr int kDy[9] = {0, -1, -1, 0, 1, 1, 1, 0, -1};
inline uint8_t d8_code(int dx, int dy) {
  for (uint8_t k = 1; k <= 8; ++k)
    if (kDx[k] == dx && kDy[k] == dy) return k;
  return kOutlet;
}

// Heights are the blocks' quantized integers; kNoData where no cell.
inline constexpr int32_t kNoData = INT32_MIN;

// Upstream areas are integers of 1/4096 m^2, so sums are exact in any order
// (the out-of-core result equals the in-memory one bit for bit).
inline constexpr double kAreaUnitsPerM2 = 4096;

struct Chunk {
  int64_t x0 = 0, y0 = 0;  // first cell
  int w = 0, h = 0;        // cells
  int64_t col = 0, row = 0;
  // Index among the perimeter cells (the chunk's outer ring), or -1 inside.
  int perimeter_index(int x, int y) const;
  int perimeter_count() const { return h == 1 || w == 1 ? w * h : 2 * w + 2 * (h - 2); }
  void perimeter_cell(int i, int& x, int& y) const;
  size_t cells() const { return size_t(w) * h; }
};

class FlowGrid {
 public:
  // `finest`: the tile ids of the package's finest zoom; `chunk`: C, a power
  // of two of at least 2.
  FlowGrid(const tileformat::Tiling& tiling, int zoom, int block_size,
           const std::vector<tileformat::TileId>& finest, int64_t chunk);

  const tileformat::Tiling& tiling() const { return tiling_; }
  int zoom() const { return zoom_; }
  int steps() const { return steps_; }  // cells per tile side
  int64_t width() const { return width_; }
  int64_t height() const { return height_; }
  bool wraps() const { return wrap_; }
  int64_t chunk_size() const { return c_; }
  int64_t chunks_x() const { return chunks_x_; }
  int64_t chunks_y() const { return chunks_y_; }

  // Present chunks in row-major order; slot = index here.
  const std::vector<Chunk>& chunks() const { return chunks_; }
  int slot(int64_t col, int64_t row) const {
    return col < 0 || row < 0 || col >= chunks_x_ || row >= chunks_y_
               ? -1
               : slots_[size_t(row * chunks_x_ + col)];
  }
  // The slot of the chunk holding cell (x, y) (x already wrapped), or -1.
  int slot_of(int64_t x, int64_t y) const {
    return slot(std::min(x / c_, chunks_x_ - 1), std::min(y / c_, chunks_y_ - 1));
  }
  // Wraps x east-west where the grid wraps; false when (x, y) is off the grid.
  bool normalise(int64_t& x, int64_t y) const {
    if (y < 0 || y >= height_) return false;
    if (x < 0 || x >= width_) {
      if (!wrap_) return false;
      x = ((x % width_) + width_) % width_;
    }
    return true;
  }

  // The chunks (col, row) that tiles `finest` touch with chunk size `chunk`,
  // as flags over chunks_x * chunks_y; and those counts.
  static std::vector<uint8_t> present_chunks(const tileformat::Tiling& tiling, int zoom, int steps,
                                             const std::vector<tileformat::TileId>& finest,
                                             int64_t chunk, int64_t& chunks_x, int64_t& chunks_y);

  // Ground metres between cells of row y, and each cell's true area.
  double dx(int64_t y) const { return dx_[size_t(y)]; }
  double dy(int64_t y) const { return dy_[size_t(y)]; }
  uint64_t area_units(int64_t y) const { return area_[size_t(y)]; }

 private:
  tileformat::Tiling tiling_;
  int zoom_, steps_;
  int64_t width_, height_, c_, chunks_x_, chunks_y_;
  bool wrap_;
  std::vector<Chunk> chunks_;
  std::vector<int> slots_;
  std::vector<double> dx_, dy_;
  std::vector<uint64_t> area_;
};

// The area of one cell of row `y` in m^2 on the WGS84 ellipsoid (geodetic,
// webmercator) or the plane (local): the zone between the row's northern
// and southern cell edges, clipped at the poles.
double cell_area_m2(const tileformat::Tiling& tiling, int zoom, int steps, int64_t y);

}  // namespace globe::flow
