// Height windows across block edges (see height_window.hpp).
#include "analysis/height_window.hpp"

#include <algorithm>
#include <set>

namespace globe {

using tileformat::TileId;

std::vector<TileId> tiles_around(const tileformat::Tiling& t, TileId id, int radius) {
  std::vector<TileId> out;
  std::set<TileId> seen;
  const int64_t nx = static_cast<int64_t>(t.tiles_x(id.z)),
                ny = static_cast<int64_t>(t.tiles_y(id.z));
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx) {
      int64_t x = int64_t(id.x) + dx;
      const int64_t y = int64_t(id.y) + dy;
      if (y < 0 || y >= ny) continue;
      if (x < 0 || x >= nx) {
        if (t.wrap_tiles() == 0) continue;
        x = ((x % nx) + nx) % nx;
      }
      const TileId tile{id.z, uint32_t(x), uint32_t(y)};
      if (seen.insert(tile).second) out.push_back(tile);
    }
  return out;
}

HeightWindow::HeightWindow(const tileformat::Tiling& tiling, TileId id, int size, int halo,
                           const BlockLookup& block)
    : size_(size), halo_(halo), width_(size + 2 * halo) {
  h_.assign(size_t(width_) * width_, 0);
  ok_.assign(size_t(width_) * width_, 0);
  const int n = size - 1;  // blocks share their edge samples
  const int radius = radius_for(size, halo);
  const int64_t nx = static_cast<int64_t>(tiling.tiles_x(id.z));
  const bool wraps = tiling.wrap_tiles() != 0;
  // Each window column's tile column and sample in it; the block itself is
  // written last so that its own samples win over shared edges of others.
  for (int pass = 0; pass < 2; ++pass)
    for (int ty = -radius; ty <= radius; ++ty)
      for (int tx = -radius; tx <= radius; ++tx) {
        const bool self = tx == 0 && ty == 0;
        if (self != (pass == 1)) continue;
        int64_t x = int64_t(id.x) + tx;
        const int64_t y = int64_t(id.y) + ty;
        if (y < 0 || y >= int64_t(tiling.tiles_y(id.z))) continue;
        if (x < 0 || x >= nx) {
          if (!wraps) continue;  // (a narrow zoom reads the same tile on both sides)
          x = ((x % nx) + nx) % nx;
        }
        const tileformat::MBlock* b = block(TileId{id.z, uint32_t(x), uint32_t(y)});
        if (!b) continue;
        const int y0 = std::max(-halo, ty * n), y1 = std::min(size - 1 + halo, ty * n + n);
        const int x0 = std::max(-halo, tx * n), x1 = std::min(size - 1 + halo, tx * n + n);
        for (int wy = y0; wy <= y1; ++wy)
          for (int wx = x0; wx <= x1; ++wx) {
            const int bx = wx - tx * n, by = wy - ty * n;
            const size_t k = index(wx, wy);
            if (!self && ok_[k]) continue;  // an equal shared edge sample is there
            h_[k] = static_cast<float>(b->height(bx, by));
            ok_[k] = b->is_valid(bx, by) ? 1 : 0;
          }
      }
  invalid_before_.assign(size_t(width_) * (width_ + 1), 0);
  for (int y = 0; y < width_; ++y) {
    uint16_t* c = &invalid_before_[size_t(y) * (width_ + 1)];
    const uint8_t* ok = &ok_[size_t(y) * width_];
    for (int x = 0; x < width_; ++x)
      c[x + 1] = uint16_t(c[x] + (ok[x] ? 0 : 1));
  }
}

}  // namespace globe
