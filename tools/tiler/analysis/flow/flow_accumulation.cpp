// Tiled flow accumulation (see flow_accumulation.hpp).
#include "analysis/flow/flow_accumulation.hpp"

namespace globe::flow {

std::vector<uint64_t> accumulate_chunk(const FlowGrid& g, const Chunk& c,
                                       const std::vector<uint8_t>& rec,
                                       const std::vector<uint64_t>& inflow,
                                       PerimeterFlow* perimeter) {
  const int w = c.w, h = c.h;
  const size_t n = c.cells();
  // The index step to each D8 receiver, and whether (x, y)'s receiver lies
  // inside the chunk.
  int64_t step[9];
  for (int d = 0; d < 9; ++d)
    step[d] = int64_t(kDy[d]) * w + kDx[d];
  auto inside = [&](int x, int y, uint8_t d) {
    if (d == kOutlet || d == kNoDataCode) return false;
    const int rx = x + kDx[d], ry = y + kDy[d];
    return rx >= 0 && ry >= 0 && rx < w && ry < h;
  };
  // Own areas (plus inflow at the perimeter) and donor counts.
  std::vector<uint64_t> acc(n, 0);
  std::vector<uint8_t> donors(n, 0);
  for (int y = 0; y < h; ++y) {
    const uint64_t area = g.area_units(c.y0 + y);
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      const uint8_t d = rec[i];
      if (d == kNoDataCode) continue;
      acc[i] = area;
      if (inside(x, y, d)) ++donors[size_t(int64_t(i) + step[d])];
    }
  }
  if (!inflow.empty())
    for (int p = 0; p < c.perimeter_count(); ++p) {
      int x, y;
      c.perimeter_cell(p, x, y);
      acc[size_t(y) * w + x] += inflow[size_t(p)];
    }
  // Topological order without a queue: from each cell without donors, in
  // row order, follow the water down while the cell reached has no donor
  // left to wait for. Consecutive cells are neighbours, so this stays in
  // cache where a breadth-first order jumps across the chunk. kDone marks
  // a cell passed on.
  constexpr uint8_t kDone = 0xff;
  for (int y0 = 0; y0 < h; ++y0)
    for (int x0 = 0; x0 < w; ++x0) {
      size_t i = size_t(y0) * w + x0;
      if (donors[i] != 0 || rec[i] == kNoDataCode) continue;
      int x = x0, y = y0;
      while (true) {
        donors[i] = kDone;
        const uint8_t d = rec[i];
        if (!inside(x, y, d)) break;
        const size_t r = size_t(int64_t(i) + step[d]);
        acc[r] += acc[i];
        if (--donors[r] != 0) break;
        i = r, x += kDx[d], y += kDy[d];
      }
    }
  if (!perimeter) return acc;
  // Per perimeter cell, the first perimeter cell downstream inside the
  // chunk: followed down, each interior cell remembering the answer for
  // the walks that reach it later (kUnknown until then).
  constexpr int32_t kUnknown = -2;
  std::vector<int32_t> below(n, kUnknown);
  std::vector<size_t> path;
  auto first_below = [&](int x, int y) {
    path.clear();
    int32_t found = -1;
    size_t i = size_t(y) * w + x;
    while (true) {
      const uint8_t d = rec[i];
      if (!inside(x, y, d)) break;
      i = size_t(int64_t(i) + step[d]), x += kDx[d], y += kDy[d];
      const int rp = c.perimeter_index(x, y);
      if (rp >= 0) {
        found = rp;
        break;
      }
      if (below[i] != kUnknown) {
        found = below[i];
        break;
      }
      path.push_back(i);
    }
    for (size_t k : path)
      below[k] = found;
    return found;
  };
  const int count = c.perimeter_count();
  perimeter->area.assign(size_t(count), 0);
  perimeter->next.assign(size_t(count), -1);
  perimeter->leaves.assign(size_t(count), 0);
  for (int p = 0; p < count; ++p) {
    int x, y;
    c.perimeter_cell(p, x, y);
    const size_t i = size_t(y) * w + x;
    const uint8_t d = rec[i];
    perimeter->area[size_t(p)] = acc[i];
    perimeter->next[size_t(p)] = first_below(x, y);
    perimeter->leaves[size_t(p)] = d != kOutlet && d != kNoDataCode && !inside(x, y, d);
  }
  return acc;
}

std::vector<uint64_t> solve_inflows(const std::vector<uint64_t>& area,
                                    const std::vector<int64_t>& successor,
                                    const std::vector<uint8_t>& crosses) {
  const size_t n = area.size();
  std::vector<uint32_t> preds(n, 0);
  for (size_t i = 0; i < n; ++i)
    if (successor[i] != kNoNode) ++preds[size_t(successor[i])];
  // received: from other chunks, directly or through perimeter cells
  // upstream inside the own chunk; inflow: from other chunks directly.
  std::vector<uint64_t> received(n, 0), inflow(n, 0);
  std::vector<uint32_t> order;  // (perimeter cells are far fewer than 2^32)
  order.reserve(n);
  for (size_t i = 0; i < n; ++i)
    if (preds[i] == 0) order.push_back(uint32_t(i));
  for (size_t head = 0; head < order.size(); ++head) {
    const size_t i = order[head];
    const int64_t s = successor[i];
    if (s == kNoNode) continue;
    if (crosses[i]) {
      inflow[size_t(s)] += area[i] + received[i];
      received[size_t(s)] += area[i] + received[i];
    } else {
      received[size_t(s)] += received[i];
    }
    if (--preds[size_t(s)] == 0) order.push_back(uint32_t(s));
  }
  return inflow;
}

}  // namespace globe::flow
