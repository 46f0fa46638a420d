// Tiled flow accumulation (see flow_accumulation.hpp).
#include "flow_accumulation.hpp"

namespace globe::flow {

std::vector<uint64_t> accumulate_chunk(const FlowGrid& g, const Chunk& c,
                                       const std::vector<uint8_t>& rec,
                                       const std::vector<uint64_t>& inflow,
                                       PerimeterFlow* perimeter) {
  const int w = c.w, h = c.h;
  const size_t n = c.cells();
  // Each cell's receiver inside the chunk, or -1; own areas; donor counts.
  std::vector<int32_t> down(n, -1);
  std::vector<uint64_t> acc(n, 0);
  std::vector<uint8_t> donors(n, 0);
  for (int y = 0; y < h; ++y) {
    const uint64_t area = g.area_units(c.y0 + y);
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      const uint8_t d = rec[i];
      if (d == kNoDataCode) continue;
      acc[i] = area;
      if (d == kOutlet) continue;
      const int rx = x + kDx[d], ry = y + kDy[d];
      if (rx < 0 || ry < 0 || rx >= w || ry >= h) continue;
      down[i] = ry * w + rx;
      ++donors[size_t(down[i])];
    }
  }
  if (!inflow.empty())
    for (int p = 0; p < c.perimeter_count(); ++p) {
      int x, y;
      c.perimeter_cell(p, x, y);
      acc[size_t(y) * w + x] += inflow[size_t(p)];
    }
  // Kahn's order: a cell is final once all its donors have passed on.
  std::vector<uint32_t> order;
  order.reserve(n);
  for (size_t i = 0; i < n; ++i)
    if (rec[i] != kNoDataCode && donors[i] == 0) order.push_back(uint32_t(i));
  for (size_t head = 0; head < order.size(); ++head) {
    const int32_t r = down[order[head]];
    if (r < 0) continue;
    acc[size_t(r)] += acc[order[head]];
    if (--donors[size_t(r)] == 0) order.push_back(uint32_t(r));
  }
  if (!perimeter) return acc;
  // Downstream first: the first perimeter cell below each cell.
  std::vector<int32_t> below(n, -1);
  for (size_t k = order.size(); k-- > 0;) {
    const size_t i = order[k];
    const int32_t r = down[i];
    if (r < 0) continue;
    const int rp = c.perimeter_index(r % w, r / w);
    below[i] = rp >= 0 ? rp : below[size_t(r)];
  }
  const int count = c.perimeter_count();
  perimeter->area.assign(size_t(count), 0);
  perimeter->next.assign(size_t(count), -1);
  perimeter->leaves.assign(size_t(count), 0);
  for (int p = 0; p < count; ++p) {
    int x, y;
    c.perimeter_cell(p, x, y);
    const size_t i = size_t(y) * w + x;
    perimeter->area[size_t(p)] = acc[i];
    perimeter->next[size_t(p)] = below[i];
    const uint8_t d = rec[i];
    perimeter->leaves[size_t(p)] = d != kOutlet && d != kNoDataCode && down[i] < 0;
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
