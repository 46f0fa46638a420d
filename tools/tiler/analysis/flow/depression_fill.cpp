// Tiled priority-flood depression filling (see depression_fill.hpp).
#include "depression_fill.hpp"

#include <algorithm>
#include <deque>
#include <queue>
#include <unordered_map>

namespace globe::flow {

namespace {

struct Open {
  int32_t level;
  uint32_t seq;  // first pushed, first popped among equal levels
  uint32_t cell;
  bool operator>(const Open& o) const { return level != o.level ? level > o.level : seq > o.seq; }
};

enum : uint8_t { kNew = 0, kQueued = 1, kClosed = 2 };

}  // namespace

ChunkFill fill_chunk(const Chunk& c, const std::vector<int32_t>& z) {
  const ChunkWindow win(c);
  const int w = c.w, h = c.h;
  ChunkFill out;
  out.filled.assign(c.cells(), kNoData);
  out.label.assign(c.cells(), 0);
  std::vector<uint8_t> state(c.cells(), kNew);
  std::priority_queue<Open, std::vector<Open>, std::greater<Open>> open;
  std::deque<uint32_t> pit;  // cells at the level being flooded: no heap needed
  uint32_t seq = 0;
  auto seed = [&](int x, int y) {
    const uint32_t i = uint32_t(y) * w + x;
    const size_t k = win.at(x, y);
    if (z[k] == kNoData || state[i] != kNew) return;
    state[i] = kQueued;
    out.filled[i] = z[k];
    if (at_data_edge(z, k, win.stride())) out.label[i] = kEdgeLabel;
    open.push({z[k], seq++, i});
  };
  // Seeds: the cells next to no data (anywhere) and the chunk's perimeter.
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t k = win.at(x, y);
      if (z[k] != kNoData && at_data_edge(z, k, win.stride())) seed(x, y);
    }
  for (int i = 0; i < c.perimeter_count(); ++i) {
    int x, y;
    c.perimeter_cell(i, x, y);
    seed(x, y);
  }
  std::unordered_map<uint64_t, int32_t> spill;
  auto note_spill = [&](uint32_t a, uint32_t b, int32_t level) {
    if (a > b) std::swap(a, b);
    const uint64_t key = (uint64_t(a) << 32) | b;
    auto [it, fresh] = spill.emplace(key, level);
    if (!fresh && level < it->second) it->second = level;
  };
  while (!pit.empty() || !open.empty()) {
    uint32_t i;
    if (!pit.empty()) {
      i = pit.front();
      pit.pop_front();
    } else {
      i = open.top().cell;
      open.pop();
    }
    if (state[i] == kClosed) continue;
    state[i] = kClosed;
    if (out.label[i] == 0) out.label[i] = out.labels++;
    const int x = int(i % w), y = int(i / w);
    const int32_t level = out.filled[i];
    for (int d = 1; d <= 8; ++d) {
      const int nx = x + kDx[d], ny = y + kDy[d];
      if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
      const uint32_t n = uint32_t(ny) * w + nx;
      const int32_t zn = z[win.at(nx, ny)];
      if (zn == kNoData) continue;
      if (state[n] == kClosed) {
        if (out.label[n] != out.label[i])
          note_spill(out.label[i], out.label[n], std::max(level, out.filled[n]));
        continue;
      }
      if (state[n] == kQueued) {
        // A perimeter seed not yet reached: it joins this watershed.
        if (out.label[n] == 0) out.label[n] = out.label[i];
        continue;
      }
      state[n] = kQueued;
      out.label[n] = out.label[i];
      if (zn <= level) {
        out.filled[n] = level;
        pit.push_back(n);
      } else {
        out.filled[n] = zn;
        open.push({zn, seq++, n});
      }
    }
  }
  out.edges.reserve(spill.size());
  for (const auto& [key, level] : spill)
    out.edges.push_back({uint32_t(key >> 32), uint32_t(key), level});
  std::sort(out.edges.begin(), out.edges.end(), [](const SpillEdge& p, const SpillEdge& q) {
    return p.a != q.a ? p.a < q.a : p.b < q.b;
  });
  return out;
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
