// D8 directions and flat routing (see flow_directions.hpp).
#include "analysis/flow/flow_directions.hpp"

#include <algorithm>
#include <cmath>

#include "analysis/flow/depression_fill.hpp"

namespace globe::flow {

std::vector<uint32_t> classify_flats(const Chunk& c, const std::vector<int32_t>& f,
                                     std::vector<uint32_t>& dist, std::vector<int32_t>& key) {
  const ChunkWindow win(c);
  const int s = win.stride();
  std::vector<uint32_t> flats;
  for (int y = 0; y < c.h; ++y)
    for (int x = 0; x < c.w; ++x) {
      const size_t k = win.at(x, y);
      if (f[k] == kNoData) continue;
      int32_t lowest = f[k];
      bool edge = false;
      for (int d = 1; d <= 8; ++d) {
        const int32_t fn = f[k + ptrdiff_t(kDy[d]) * s + kDx[d]];
        edge |= fn == kNoData;
        if (fn != kNoData && fn < lowest) lowest = fn;
      }
      const bool flat = !edge && lowest == f[k];
      dist[k] = flat ? kFar : 0;
      key[k] = flat ? kNoKey : lowest;
      if (flat) flats.push_back(uint32_t(k));
    }
  return flats;
}

void settle_flats(const Chunk& c, const std::vector<int32_t>& f, std::vector<uint32_t>& dist,
                  std::vector<int32_t>& key, const std::vector<uint32_t>& flats) {
  if (flats.empty()) return;
  const ChunkWindow win(c);
  const int s = win.stride();
  // 1: the flat cells to settle; 2: a source listed below.
  std::vector<uint8_t> open(win.size(), 0);
  for (uint32_t k : flats)
    open[k] = 1;
  // Breadth-first with unit steps from every cell off a flat (distance 0)
  // and the ring's known distances, into the chunk's flat cells of the same
  // height. Sources: known cells next to a flat cell of their height, in
  // order of distance (those off a flat first, then the ring's, sorted);
  // reached cells queue in order of distance (each one step beyond the cell
  // it came from), so taking the nearer of the two fronts settles cells in
  // order of distance, each at its least.
  using Source = std::pair<uint32_t, uint32_t>;  // distance, window index
  std::vector<Source> sources, ring_sources;
  for (uint32_t k : flats)
    for (int d = 1; d <= 8; ++d) {
      const size_t n = size_t(ptrdiff_t(k) + ptrdiff_t(kDy[d]) * s + kDx[d]);
      if (f[n] != f[k] || dist[n] == kFar || open[n] != 0) continue;
      open[n] = 2;
      (dist[n] == 0 ? sources : ring_sources).push_back({dist[n], uint32_t(n)});
    }
  std::sort(ring_sources.begin(), ring_sources.end());
  sources.insert(sources.end(), ring_sources.begin(), ring_sources.end());
  std::vector<Source>().swap(ring_sources);
  // Keys on the way: a cell's is the least of its neighbours' one step
  // nearer, each of which passes its own on when it is taken (all of them
  // before the cell itself is).
  std::vector<uint32_t> front;  // settled flat cells not yet taken, nearest first
  size_t next_source = 0, next_front = 0;
  while (next_source < sources.size() || next_front < front.size()) {
    uint32_t k;
    if (next_front < front.size() &&
        (next_source == sources.size() || dist[front[next_front]] <= sources[next_source].first))
      k = front[next_front++];
    else
      k = sources[next_source++].second;
    if (next_front >= 4096 && 2 * next_front >= front.size()) {  // the taken ones go
      front.erase(front.begin(), front.begin() + ptrdiff_t(next_front));
      next_front = 0;
    }
    const uint32_t d = dist[k];
    const int32_t passed = key[k];
    for (int dir = 1; dir <= 8; ++dir) {
      // A ring cell's outer neighbours lie off the window (or wrap to the
      // ring's other side, which is never open).
      const ptrdiff_t n = ptrdiff_t(k) + ptrdiff_t(kDy[dir]) * s + kDx[dir];
      if (n < 0 || size_t(n) >= open.size() || open[size_t(n)] != 1 || f[size_t(n)] != f[k])
        continue;
      uint32_t& dn = dist[size_t(n)];
      int32_t& kn = key[size_t(n)];
      if (dn > d + 1) {
        dn = d + 1;
        kn = passed;
        front.push_back(uint32_t(n));
      } else if (dn == d + 1) {
        kn = std::min(kn, passed);
      }
    }
  }
}

void flat_distances(const Chunk& c, const std::vector<int32_t>& f, std::vector<uint32_t>& dist,
                    std::vector<int32_t>& key) {
  settle_flats(c, f, dist, key, classify_flats(c, f, dist, key));
}

std::vector<uint32_t> flats_next_to(const Chunk& c, const std::vector<int32_t>& f,
                                    const std::vector<uint32_t>& dist,
                                    const std::vector<uint8_t>& changed) {
  const ChunkWindow win(c);
  const int s = win.stride();
  auto inside = [&](size_t k) {
    const int x = int(k % size_t(s)) - 1, y = int(k / size_t(s)) - 1;
    return x >= 0 && y >= 0 && x < c.w && y < c.h;
  };
  std::vector<uint8_t> taken(win.size(), 0);
  std::vector<uint32_t> cells;
  for (size_t r = 0; r < changed.size(); ++r) {
    if (!changed[r] || f[r] == kNoData) continue;
    for (int d = 1; d <= 8; ++d) {
      const ptrdiff_t n = ptrdiff_t(r) + ptrdiff_t(kDy[d]) * s + kDx[d];
      if (n < 0 || size_t(n) >= f.size() || !inside(size_t(n)) || taken[size_t(n)] ||
          f[size_t(n)] != f[r] || dist[size_t(n)] == 0)
        continue;
      // The flat of cell n: its 8-connected cells of one height, all flat.
      const size_t first = cells.size();
      taken[size_t(n)] = 1;
      cells.push_back(uint32_t(n));
      for (size_t i = first; i < cells.size(); ++i)
        for (int e = 1; e <= 8; ++e) {
          const size_t m = size_t(ptrdiff_t(cells[i]) + ptrdiff_t(kDy[e]) * s + kDx[e]);
          if (!inside(m) || taken[m] || f[m] != f[r] || dist[m] == 0) continue;
          taken[m] = 1;
          cells.push_back(uint32_t(m));
        }
    }
  }
  return cells;
}

std::vector<uint8_t> d8_receivers(const FlowGrid& g, const Chunk& c, const std::vector<int32_t>& f,
                                  const std::vector<uint32_t>& dist,
                                  const std::vector<int32_t>& key) {
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
      if (best == kOutlet && !at_data_edge(f, k, s) && dist[k] != kFar && dist[k] > 0) {
        int32_t least = 0;
        for (int d = 1; d <= 8; ++d) {
          const size_t n = size_t(ptrdiff_t(k) + ptrdiff_t(kDy[d]) * s + kDx[d]);
          if (f[n] == f[k] && dist[n] + 1 == dist[k] && (best == kOutlet || key[n] < least)) {
            best = uint8_t(d);
            least = key[n];
          }
        }
      }
      out[size_t(y) * c.w + x] = best;
    }
  }
  return out;
}

}  // namespace globe::flow
