// Routing through filled depressions. Filling makes a depression a flat at
// its spill level; crossing that flat by the shortest way (flow_directions)
// sends a river straight across, where a search in height order from the
// edges (GRASS r.watershed's A*, and the way water rises in a real basin)
// runs down into the depression and out along the valley it was entered by.
// A depression here is a set of 8-connected cells whose raw height lies below
// the filled surface (all at one level L). It is entered at its rim cell of
// level L that the flat routing reaches first (least flat distance, then
// least key, then grid position); from there a search in order of raw
// height (earlier first among equal heights; orthogonal neighbours before
// diagonal ones) gives each cell of the depression the neighbour that first
// reached it as receiver, a diagonal yielding to the orthogonal neighbour
// between when the climb from that one is steeper. The entry itself keeps
// its flat route, which never leads back into the depression (its next cell
// is nearer the flat's exit than any rim cell). Everything depends only on
// the whole grid (not on chunks): the solver gathers depressions that cross
// chunk edges (flow_solver.cpp). docs/analysis.md, "Flow".
#pragma once

#include <cstdint>
#include <tuple>
#include <vector>

#include "analysis/flow/flow_directions.hpp"
#include "analysis/flow/flow_grid.hpp"
#include "analysis/flow/height_queue.hpp"

namespace globe::flow {

// A rectangle of grid cells, row-major: raw and filled heights (kNoData
// where none). (x0, y0): the grid cell of index 0, before wrapping.
struct HeightPatch {
  int64_t x0 = 0, y0 = 0;
  int w = 0, h = 0;
  std::vector<int32_t> raw, filled;
  bool in_depression(size_t i) const { return raw[i] != kNoData && raw[i] < filled[i]; }
};

// How early the flat routing reaches a rim cell: (flat distance, key, grid
// position y * width + x); the least is the entry.
using EntryRank = std::tuple<uint32_t, int32_t, int64_t>;

// The entry of a depression (`cells`, patch indices): its rim cell of the
// depression's level with a known flat distance (`distance`, `key`: per
// patch cell) of least rank, only looking next to the cells for which
// `mine` holds. False where none.
template <typename Mine>
bool depression_entry(const FlowGrid& grid, const HeightPatch& p,
                      const std::vector<uint32_t>& cells, const std::vector<uint32_t>& distance,
                      const std::vector<int32_t>& key, Mine mine, EntryRank& rank, uint32_t& entry);

class DepressionRouter {
 public:
  explicit DepressionRouter(const HeightPatch& patch);

  // The depression holding cell `seed` (its patch indices), marking its
  // cells seen; `reaches_ring` tells whether it touches the patch's outer
  // ring (it may go on outside the patch).
  std::vector<uint32_t> depression(uint32_t seed, bool& reaches_ring);
  bool seen(uint32_t i) const { return state_[i] != kOutside; }

  // Receiver codes for the depression's `cells`, searched from `entry` (a
  // patch index of a rim cell): calls out(index, code) for each cell.
  template <typename Out>
  void route(const FlowGrid& grid, const std::vector<uint32_t>& cells, uint32_t entry, Out out) {
    search(grid, cells, entry);
    for (uint32_t i : cells)
      if (state(i) == kWorked) out(i, uint8_t(state_[i] >> 4));  // (every cell is reached)
    for (uint32_t i : cells)
      state_[i] = kDone;
  }

 private:
  // Per cell its state (low 3 bits) and, once queued, its receiver code
  // (high 4 bits).
  enum : uint8_t { kOutside = 0, kMember, kQueued, kWorked, kDone, kStateMask = 7 };
  uint8_t state(size_t i) const { return state_[i] & kStateMask; }
  void search(const FlowGrid& grid, const std::vector<uint32_t>& cells, uint32_t entry);

  const HeightPatch& p_;
  std::vector<uint8_t> state_;
  std::vector<double> diagonal_;  // per patch row, once first needed (else -1)
  HeightQueue queue_;             // the search's, kept between depressions
};

template <typename Mine>
bool depression_entry(const FlowGrid& g, const HeightPatch& p, const std::vector<uint32_t>& cells,
                      const std::vector<uint32_t>& distance, const std::vector<int32_t>& key,
                      Mine mine, EntryRank& rank, uint32_t& entry) {
  bool found = false;
  for (uint32_t i : cells) {
    if (!mine(i)) continue;
    const int32_t level = p.filled[i];
    const int x = int(i % uint32_t(p.w)), y = int(i / uint32_t(p.w));
    for (int d = 1; d <= 8; ++d) {
      const int nx = x + kDx[d], ny = y + kDy[d];
      if (nx < 0 || ny < 0 || nx >= p.w || ny >= p.h) continue;
      const uint32_t n = uint32_t(ny * p.w + nx);
      if (p.filled[n] != level || p.in_depression(n) || distance[n] == kFar) continue;
      int64_t gx = p.x0 + nx;
      const int64_t gy = p.y0 + ny;
      if (!g.normalise(gx, gy)) continue;
      const EntryRank r{distance[n], key[n], gy * g.width() + gx};
      if (!found || r < rank) rank = r, entry = n, found = true;
    }
  }
  return found;
}

}  // namespace globe::flow
