// Routing through filled depressions (see depression_routing.hpp).
#include "analysis/flow/depression_routing.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

namespace globe::flow {

namespace {

// Neighbour order of the search: orthogonal (N, E, S, W), then diagonal
// (NE, SE, SW, NW), as D8 codes.
constexpr uint8_t kOrder[8] = {1, 3, 5, 7, 2, 4, 6, 8};
// For a diagonal code, the two orthogonal codes between the cell and that
// neighbour: the one sharing the neighbour's row (a step east or west away
// from it), and the one sharing its column (north or south).
uint8_t same_row(uint8_t diagonal) {
  return kDy[diagonal] < 0 ? 1 : 5;  // N or S of the cell
}
uint8_t same_column(uint8_t diagonal) {
  return kDx[diagonal] > 0 ? 3 : 7;  // E or W of the cell
}

}  // namespace

DepressionRouter::DepressionRouter(const HeightPatch& patch)
    : p_(patch), state_(size_t(patch.w) * patch.h, kOutside), diagonal_(size_t(patch.h), -1) {}

std::vector<uint32_t> DepressionRouter::depression(uint32_t seed, bool& reaches_ring) {
  reaches_ring = false;
  std::vector<uint32_t> cells{seed};
  state_[seed] = kMember;
  for (size_t k = 0; k < cells.size(); ++k) {
    const int x = int(cells[k] % uint32_t(p_.w)), y = int(cells[k] / uint32_t(p_.w));
    if (x == 0 || y == 0 || x == p_.w - 1 || y == p_.h - 1) {
      reaches_ring = true;
      continue;  // its outer neighbours lie off the patch
    }
    for (int d = 1; d <= 8; ++d) {
      const uint32_t n = uint32_t((y + kDy[d]) * p_.w + x + kDx[d]);
      if (state(n) != kOutside || !p_.in_depression(n)) continue;
      state_[n] = kMember;
      cells.push_back(n);
    }
  }
  return cells;
}

void DepressionRouter::search(const FlowGrid& g, const std::vector<uint32_t>& cells,
                              uint32_t entry) {
  // The lowest raw height first, then the earliest queued (the entry, a rim
  // cell at the depression's level, and its cells).
  int32_t lowest = p_.raw[entry], highest = lowest;
  for (uint32_t c : cells) {
    lowest = std::min(lowest, p_.raw[c]);
    highest = std::max(highest, p_.raw[c]);
  }
  HeightQueue& q = queue_;
  q.reset(lowest, highest, cells.size() + 1);
  q.push(p_.raw[entry], entry);
  bool entry_worked = false;
  while (!q.empty()) {
    const uint32_t i = q.pop();
    const int x = int(i % uint32_t(p_.w)), y = int(i / uint32_t(p_.w));
    const int64_t gy = p_.y0 + y;
    const double dx = g.dx(gy), dy = g.dy(gy);
    double& diagonal = diagonal_[size_t(y)];
    if (diagonal < 0) diagonal = std::hypot(dx, dy);
    const double length[9] = {0, dy, diagonal, dx, diagonal, dy, diagonal, dx, diagonal};
    // Climbs to the neighbours not yet worked (0 where none or downhill).
    double climb[9] = {0};
    int64_t at[9] = {0};
    int32_t raw[9];
    raw[0] = p_.raw[i];
    for (uint8_t d : kOrder) {
      const int nx = x + kDx[d], ny = y + kDy[d];
      at[d] = -1;
      if (nx < 0 || ny < 0 || nx >= p_.w || ny >= p_.h) continue;
      const uint32_t n = uint32_t(ny * p_.w + nx);
      raw[d] = p_.raw[n];
      if (raw[d] == kNoData) continue;
      at[d] = n;
      const bool worked = state(n) == kWorked || (n == entry && entry_worked);
      if (!worked && raw[d] > raw[0]) climb[d] = double(raw[d] - raw[0]) / length[d];
    }
    for (uint8_t d : kOrder) {
      if (at[d] < 0) continue;
      const uint32_t n = uint32_t(at[d]);
      if (state(n) != kMember) continue;  // not of this depression, or reached
      if (d % 2 == 0 && climb[d] > 0) {
        // A diagonal yields where the climb from the orthogonal neighbour
        // between (higher than this cell) to it is steeper.
        bool yield = false;
        for (uint8_t o : {same_row(d), same_column(d)}) {
          if (climb[o] <= 0 || at[o] < 0) continue;
          const double step = o == same_row(d) ? dx : dy;
          if (raw[d] > raw[o] && climb[d] < double(raw[d] - raw[o]) / step) yield = true;
        }
        if (yield) continue;
      }
      state_[n] = uint8_t(kQueued | d8_code(-kDx[d], -kDy[d]) << 4);
      q.push(raw[d], n);
    }
    if (i == entry)
      entry_worked = true;
    else
      state_[i] = uint8_t((state_[i] & ~kStateMask) | kWorked);
  }
}

}  // namespace globe::flow
