// Tiled priority-flood depression filling (see depression_fill.hpp).
#include "analysis/flow/depression_fill.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <queue>

namespace globe::flow {

namespace {

// The open cells of the flood, least level first: a radix heap (Ahuja et al.
// 1990), which needs only that no level pushed is below the last popped —
// true here, as a cell is pushed at its own height above the level being
// flooded (lower ones go to the pit queue). Cells of one level come out in
// any order: the filled surface does not depend on it (only which watershed
// label a cell takes, and the spill levels make those agree).
class OpenCells {
 public:
  bool empty() const { return size_ == 0; }
  void push(int32_t level, uint32_t cell) {
    const uint32_t key = uint32_t(level) ^ 0x80000000u;  // order-preserving
    bucket_[bucket_of(key)].push_back({key, cell});
    ++size_;
  }
  uint32_t pop() {
    if (bucket_[0].empty()) {
      size_t i = 1;
      while (bucket_[i].empty())
        ++i;
      uint32_t least = UINT32_MAX;
      for (const Item& e : bucket_[i])
        least = std::min(least, e.key);
      last_ = least;
      for (const Item& e : bucket_[i])
        bucket_[bucket_of(e.key)].push_back(e);
      bucket_[i].clear();
    }
    const uint32_t cell = bucket_[0].back().cell;
    bucket_[0].pop_back();
    --size_;
    return cell;
  }

 private:
  struct Item {
    uint32_t key, cell;
  };
  // 0 for the last popped key, else 1 + the highest bit where they differ.
  size_t bucket_of(uint32_t key) const {
    return key == last_ ? 0 : size_t(32 - std::countl_zero(key ^ last_));
  }
  std::array<std::vector<Item>, 33> bucket_;
  uint32_t last_ = 0;
  size_t size_ = 0;
};

enum : uint8_t { kNew = 0, kQueued = 1, kClosed = 2, kOutside = 3 };

}  // namespace

ChunkFill fill_chunk(const Chunk& c, const std::vector<int32_t>& z) {
  const ChunkWindow win(c);
  const int stride = win.stride();
  ptrdiff_t step[9];
  for (int d = 1; d <= 8; ++d)
    step[d] = ptrdiff_t(kDy[d]) * stride + kDx[d];
  // Window-indexed state; the ring (the neighbours' cells) is never entered.
  ChunkFill out;
  std::vector<int32_t>& filled = out.filled;
  std::vector<uint32_t>& label = out.label;
  filled.assign(win.size(), kNoData);
  label.assign(win.size(), 0);
  std::vector<uint8_t> state(win.size(), kOutside);
  for (int y = 0; y < c.h; ++y)
    for (int x = 0; x < c.w; ++x) {
      const size_t k = win.at(x, y);
      state[k] = z[k] == kNoData ? kOutside : kNew;
    }
  OpenCells open;
  std::vector<uint32_t> pit;  // cells at the level being flooded: no heap needed
  size_t pit_head = 0;
  auto seed = [&](size_t k) {
    if (state[k] != kNew) return;
    state[k] = kQueued;
    filled[k] = z[k];
    if (at_data_edge(z, k, stride)) label[k] = kEdgeLabel;
    open.push(z[k], uint32_t(k));
  };
  // Seeds: the cells next to no data (anywhere) and the chunk's perimeter.
  for (int y = 0; y < c.h; ++y)
    for (int x = 0; x < c.w; ++x) {
      const size_t k = win.at(x, y);
      if (state[k] == kNew && at_data_edge(z, k, stride)) seed(k);
    }
  for (int i = 0; i < c.perimeter_count(); ++i) {
    int x, y;
    c.perimeter_cell(i, x, y);
    seed(win.at(x, y));
  }
  SpillPairs spill;
  while (pit_head < pit.size() || !open.empty()) {
    size_t k;
    if (pit_head < pit.size()) {
      k = pit[pit_head++];
      if (pit_head == pit.size()) pit.clear(), pit_head = 0;
    } else {
      k = open.pop();
    }
    if (state[k] == kClosed) continue;
    state[k] = kClosed;
    if (label[k] == 0) label[k] = out.labels++;
    const int32_t level = filled[k];
    for (int d = 1; d <= 8; ++d) {
      const size_t n = size_t(ptrdiff_t(k) + step[d]);
      switch (state[n]) {
        case kOutside:
          break;
        case kClosed:
          if (label[n] != label[k]) spill.note(label[k], label[n], std::max(level, filled[n]));
          break;
        case kQueued:
          // A perimeter seed not yet reached: it joins this watershed.
          if (label[n] == 0) label[n] = label[k];
          break;
        default:  // kNew
          state[n] = kQueued;
          label[n] = label[k];
          if (z[n] <= level) {
            filled[n] = level;
            pit.push_back(uint32_t(n));
          } else {
            filled[n] = z[n];
            open.push(z[n], uint32_t(n));
          }
      }
    }
  }
  spill.append_to(out.edges);
  return out;
}

// The variant of Zhou, Sun and Fu (2016, "An efficient variant of the
// Priority-Flood algorithm for filling depressions in raster DEMs"): a cell
// found above the level it was reached from keeps its own height whatever
// the order, so it needs no heap; it climbs on through its higher
// neighbours with a plain stack, and goes to the heap only where it has a
// neighbour not yet reached at or below its height (whose level depends on
// the order). The heap holds a few cells instead of nearly all of them.
std::vector<int32_t> filled_surface(const Chunk& c, const std::vector<int32_t>& z) {
  const ChunkWindow win(c);
  const int stride = win.stride();
  ptrdiff_t step[9];
  for (int d = 1; d <= 8; ++d)
    step[d] = ptrdiff_t(kDy[d]) * stride + kDx[d];
  std::vector<int32_t> filled(win.size(), kNoData);
  std::vector<uint8_t> reached(win.size(), 1);  // the ring and no data count as reached
  for (int y = 0; y < c.h; ++y)
    for (int x = 0; x < c.w; ++x) {
      const size_t k = win.at(x, y);
      reached[k] = z[k] == kNoData;
    }
  OpenCells open;
  std::vector<uint32_t> pit, climb;
  auto seed = [&](size_t k) {
    if (reached[k]) return;
    reached[k] = 1;
    filled[k] = z[k];
    open.push(z[k], uint32_t(k));
  };
  for (int y = 0; y < c.h; ++y)
    for (int x = 0; x < c.w; ++x) {
      const size_t k = win.at(x, y);
      if (!reached[k] && at_data_edge(z, k, stride)) seed(k);
    }
  for (int i = 0; i < c.perimeter_count(); ++i) {
    int x, y;
    c.perimeter_cell(i, x, y);
    seed(win.at(x, y));
  }
  // The neighbours of cell k not yet reached, at k's filled level: those
  // at or below it fill to it (pit), the others keep their height (climb).
  auto spread = [&](size_t k) {
    const int32_t level = filled[k];
    for (int d = 1; d <= 8; ++d) {
      const size_t n = size_t(ptrdiff_t(k) + step[d]);
      if (reached[n]) continue;
      reached[n] = 1;
      if (z[n] <= level) {
        filled[n] = level;
        pit.push_back(uint32_t(n));
      } else {
        filled[n] = z[n];
        climb.push_back(uint32_t(n));
      }
    }
  };
  size_t pit_head = 0;
  while (true) {
    if (pit_head < pit.size()) {
      const size_t k = pit[pit_head++];
      if (pit_head == pit.size()) pit.clear(), pit_head = 0;
      spread(k);
    } else if (!climb.empty()) {
      const size_t k = climb.back();
      climb.pop_back();
      bool lower = false;
      for (int d = 1; d <= 8 && !lower; ++d) {
        const size_t n = size_t(ptrdiff_t(k) + step[d]);
        lower = !reached[n] && z[n] <= z[k];
      }
      if (lower)
        open.push(z[k], uint32_t(k));
      else
        spread(k);
    } else if (!open.empty()) {
      spread(open.pop());
    } else {
      break;
    }
  }
  return filled;
}

void SpillPairs::note(uint32_t a, uint32_t b, int32_t level) {
  if (a > b) std::swap(a, b);
  auto [it, fresh] = lowest_.emplace((uint64_t(a) << 32) | b, level);
  if (!fresh && level < it->second) it->second = level;
}

void SpillPairs::append_to(std::vector<SpillEdge>& edges) const {
  const size_t first = edges.size();
  for (const auto& [key, level] : lowest_)
    edges.push_back({uint32_t(key >> 32), uint32_t(key), level});
  // Sorted, so that the edges do not depend on the hash map's layout.
  std::sort(
      edges.begin() + ptrdiff_t(first), edges.end(),
      [](const SpillEdge& p, const SpillEdge& q) { return p.a != q.a ? p.a < q.a : p.b < q.b; });
}

std::vector<int32_t> spill_levels(size_t nodes, const std::vector<SpillEdge>& edges) {
  std::vector<uint64_t> first(nodes + 1, 0);
  for (const SpillEdge& e : edges) {
    ++first[e.a + 1];
    ++first[e.b + 1];
  }
  for (size_t i = 0; i < nodes; ++i)
    first[i + 1] += first[i];
  struct Arc {
    uint32_t to;
    int32_t level;
  };
  std::vector<Arc> arcs(first[nodes]);
  std::vector<uint64_t> fill(first.begin(), first.end() - 1);
  for (const SpillEdge& e : edges) {
    arcs[fill[e.a]++] = {e.b, e.level};
    arcs[fill[e.b]++] = {e.a, e.level};
  }
  // Minimax paths from node 0: the level water must rise to before it can
  // leave a watershed over the lowest chain of spills to the data's edge.
  std::vector<int32_t> level(nodes, INT32_MAX);
  std::vector<uint8_t> done(nodes, 0);
  using Item = std::pair<int32_t, uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
  level[0] = kNoData;
  q.push({kNoData, 0});
  while (!q.empty()) {
    const auto [l, n] = q.top();
    q.pop();
    if (done[n]) continue;
    done[n] = 1;
    for (uint64_t a = first[n]; a < first[n + 1]; ++a) {
      const int32_t via = std::max(l, arcs[a].level);
      if (via < level[arcs[a].to]) {
        level[arcs[a].to] = via;
        q.push({via, arcs[a].to});
      }
    }
  }
  for (int32_t& l : level)
    if (l == INT32_MAX) l = kNoData;
  return level;
}

}  // namespace globe::flow
