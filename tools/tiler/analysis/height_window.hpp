// One terrain block's heights with a halo of samples around it, assembled
// from its decoded neighbours (east-west wrapping on the global tilings), so
// that per-sample analytics read across block edges without seams. Samples
// of missing tiles and holes are marked invalid. Pure memory work, no I/O.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "tileformat/mblock.hpp"
#include "tileformat/tile_id.hpp"
#include "tileformat/tiling.hpp"

namespace globe {

// The decoded block of a tile, or null where there is none.
using BlockLookup = std::function<const tileformat::MBlock*(tileformat::TileId)>;

// The tiles within `radius` tiles of `id` (itself included), wrapped east-west
// on global tilings, clipped north-south; each tile once.
std::vector<tileformat::TileId> tiles_around(const tileformat::Tiling& tiling,
                                             tileformat::TileId id, int radius);

class HeightWindow {
 public:
  // Block `id` (size samples a side) and `halo` samples around it; halo may
  // reach several tiles away (tiles_around(id, radius_for(halo))).
  HeightWindow(const tileformat::Tiling& tiling, tileformat::TileId id, int size, int halo,
               const BlockLookup& block);
  // The tile radius a halo reaches.
  static int radius_for(int size, int halo) { return (halo + size - 2) / (size - 1); }

  // x, y in the block's sample coordinates: -halo .. size - 1 + halo.
  bool valid(int x, int y) const { return ok_[index(x, y)] != 0; }
  double height(int x, int y) const { return h_[index(x, y)]; }
  bool inside(int x, int y) const {
    return x >= -halo_ && y >= -halo_ && x < size_ + halo_ && y < size_ + halo_;
  }
  int halo() const { return halo_; }
  // Row y's heights: row(y)[x] for x in -halo .. size - 1 + halo.
  const float* row(int y) const { return &h_[index(0, y)]; }
  // Row y's data flags (1: has data), as row(y).
  const uint8_t* valid_row(int y) const { return &ok_[index(0, y)]; }
  // Whether samples x0 .. x1 of row y all have data.
  bool all_valid(int y, int x0, int x1) const {
    const size_t r = size_t(y + halo_) * (width_ + 1);
    return invalid_before_[r + size_t(x1 + halo_) + 1] == invalid_before_[r + size_t(x0 + halo_)];
  }

 private:
  size_t index(int x, int y) const { return size_t(y + halo_) * width_ + size_t(x + halo_); }
  int size_, halo_, width_;
  // Single precision: 0.1 mm at 1,000 m, well below any package's height
  // step, and half the memory the sky view's rows stream through.
  std::vector<float> h_;
  std::vector<uint8_t> ok_;
  // Per row, width + 1 counts: samples without data before each column.
  std::vector<uint16_t> invalid_before_;
};

}  // namespace globe
