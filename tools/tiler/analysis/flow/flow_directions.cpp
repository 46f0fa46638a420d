// D8 directions and flat routing (see flow_directions.hpp).
#include "flow_directions.hpp"

#include <algorithm>
#include <cmath>
#include <queue>

#include "depression_fill.hpp"

namespace globe::flow {

bool on_flat(const std::vector<int32_t>& f, size_t k, int stride) {
  if (f[k] == kNoData || at_data_edge(f, k, stride)) return false;
  for (int d = 1; d <= 8; ++d)
    if (f[k + ptrdiff_t(kDy[d]) * stride + kDx[d]] < f[k]) return false;
  return true;
}

void flat_distances(const Chunk& c, const std::vector<int32_t>& f, std::vector<uint32_t>& dist) {
  const ChunkWindow win(c);
  const int s = win.stride();
  // Dijkstra with unit steps from every cell off a flat (distance 0) and the
  // ring's known distances, into the chunk's flat cells of the same height.
  using Item = std::pair<uint32_t, uint32_t>;  // distance, window index
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
  for (int y = 0; y < c.h; ++y)
    for (int x = 0; x < c.w; ++x) {
      const size_t k = win.at(x, y);
      dist[k] = on_flat(f, k, s) ? kFar : 0;
    }
  auto feeds_flat = [&](size_t k) {  // has a chunk cell on a flat of its height
    const int x = int(k % s) - 1, y = int(k / s) - 1;
    for (int d = 1; d <= 8; ++d) {
      const int nx = x + kDx[d], ny = y + kDy[d];
      if (nx < 0 || ny < 0 || nx >= c.w || ny >= c.h) continue;
      const size_t n = win.at(nx, ny);
      if (dist[n] == kFar && f[n] == f[k]) return true;
    }
    return false;
  };
  for (size_t k = 0; k < win.size(); ++k)
    if (f[k] != kNoData && dist[k] != kFar && feeds_flat(k)) q.push({dist[k], uint32_t(k)});
  while (!q.empty()) {
    const auto [d, k] = q.top();
    q.pop();
    if (d != dist[k]) continue;
    const int x = int(k % s) - 1, y = int(k / s) - 1;
    for (int dir = 1; dir <= 8; ++dir) {
      const int nx = x + kDx[dir], ny = y + kDy[dir];
      if (nx < 0 || ny < 0 || nx >= c.w || ny >= c.h) continue;
      const size_t n = win.at(nx, ny);
      if (f[n] != f[k] || dist[n] <= d + 1) continue;  // (cells off a flat hold 0)
      dist[n] = d + 1;
      q.push({d + 1, uint32_t(n)});
    }
  }
}

std::vector<uint8_t> d8_receivers(const FlowGrid& g, const Chunk& c, const std::vector<int32_t>& f,
                                  const std::vector<uint32_t>& dist) {
  const ChunkWindow win(c);
  const int s = win.stride();
  std::vector<uint8_t> out(c.cells(), kNoDataCode);
  for (int y = 0; y < c.h; ++y) {
    const double dx = g.dx(c.y0 + y), dy = g.dy(c.y0 + y), diag = std::hypot(dx, dy);
    const double length[9] = {0, dy, diag, dx, diag, dy, diag, dx, diag};
    for (int x = 0; x < c.w; ++x) {
      const size_t k = win.at(x, y);
      if (f[k] == kNoData) continue;
      uint8_t best = kOutlet;
      double steepest = 0;
      for (int d = 1; d <= 8; ++d) {
        const int32_t fn = f[k + ptrdiff_t(kDy[d]) * s + kDx[d]];
        if (fn == kNoData || fn >= f[k]) continue;
        const double slope = (double(f[k]) - double(fn)) / length[d];
        if (slope > steepest) {
          steepest = slope;
          best = uint8_t(d);
        }
      }
      if (best == kOutlet && !at_data_edge(f, k, s) && dist[k] != kFar && dist[k] > 0)
        for (int d = 1; d <= 8; ++d) {
          const size_t n = size_t(ptrdiff_t(k) + ptrdiff_t(kDy[d]) * s + kDx[d]);
          if (f[n] == f[k] && dist[n] + 1 == dist[k]) {
            best = uint8_t(d);
            break;
          }
        }
      out[size_t(y) * c.w + x] = best;
    }
  }
  return out;
}

}  // namespace globe::flow
