// Chunk heights from terrain blocks (see chunk_heights.hpp).
#include "analysis/flow/chunk_heights.hpp"

#include <algorithm>

namespace globe::flow {

namespace {

int64_t floor_div(int64_t a, int64_t b) {
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

// Horizontal shifts under which a tile can meet the window: the window's
// columns may wrap past either end of a wrapping grid.
std::vector<int64_t> shifts(const FlowGrid& g) {
  if (!g.wraps()) return {0};
  return {-g.width(), 0, g.width()};
}

}  // namespace

std::vector<tileformat::TileId> chunk_tiles(const FlowGrid& g, const Chunk& c) {
  std::vector<tileformat::TileId> out;
  const int64_t s = g.steps();
  const int64_t tiles_x = int64_t(g.tiling().tiles_x(g.zoom()));
  const int64_t tiles_y = int64_t(g.tiling().tiles_y(g.zoom()));
  const int64_t ty0 = std::max<int64_t>(0, floor_div(c.y0 - 2, s));
  const int64_t ty1 = std::min(tiles_y - 1, floor_div(c.y0 + c.h, s));
  const int64_t tx0 = floor_div(c.x0 - 2, s), tx1 = floor_div(c.x0 + c.w, s);
  for (int64_t ty = ty0; ty <= ty1; ++ty)
    for (int64_t tx = tx0; tx <= tx1; ++tx) {
      int64_t x = tx;
      if (x < 0 || x >= tiles_x) {
        if (!g.wraps()) continue;
        x = ((x % tiles_x) + tiles_x) % tiles_x;
      }
      const tileformat::TileId id{g.zoom(), uint32_t(x), uint32_t(ty)};
      if (std::find(out.begin(), out.end(), id) == out.end()) out.push_back(id);
    }
  return out;
}

std::vector<int32_t> chunk_heights(const FlowGrid& g, const Chunk& c, const BlockLookup& block) {
  const ChunkWindow win(c);
  std::vector<int32_t> z(win.size(), kNoData);
  std::vector<uint8_t> owned(win.size(), 0);
  const int64_t s = g.steps();
  for (const tileformat::TileId& id : chunk_tiles(g, c)) {
    const tileformat::MBlock* b = block(id);
    if (!b) continue;
    const int64_t ty0 = int64_t(id.y) * s;
    const int64_t y_lo = std::max(c.y0 - 1, ty0), y_hi = std::min(c.y0 + c.h, ty0 + s);
    for (int64_t shift : shifts(g)) {
      const int64_t tx0 = int64_t(id.x) * s + shift;
      const int64_t x_lo = std::max(c.x0 - 1, tx0), x_hi = std::min(c.x0 + c.w, tx0 + s);
      for (int64_t y = y_lo; y <= y_hi; ++y)
        for (int64_t x = x_lo; x <= x_hi; ++x) {
          const int lx = int(x - tx0), ly = int(y - ty0);
          if (!b->is_valid(lx, ly)) continue;
          const size_t k = win.at(int(x - c.x0), int(y - c.y0));
          const bool owner = lx < s && ly < s;
          if (owned[k] || (!owner && z[k] != kNoData)) continue;
          z[k] = b->q[size_t(ly) * b->size + lx];
          owned[k] = owner;
        }
    }
  }
  return z;
}

}  // namespace globe::flow
