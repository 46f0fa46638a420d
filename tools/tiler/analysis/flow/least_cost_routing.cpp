// Least-cost routing (see least_cost_routing.hpp).
#include "analysis/flow/least_cost_routing.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "analysis/flow/height_queue.hpp"

namespace globe::flow {

namespace {

// The search's neighbour order, as D8 codes: S, N, W, E, then NE, SW, SE, NW.
constexpr uint8_t kOrder[8] = {5, 1, 7, 3, 2, 6, 4, 8};

enum : uint8_t { kUnseen = 0, kSeed, kQueued, kWorked };

class Search {
 public:
  Search(const FlowGrid& g, const GridWindow& win, const std::vector<int32_t>& z)
      : g_(g), win_(win), z_(z), w_(win.w), steps_(size_t(win.h) * 9) {
    for (int64_t y = 0; y < win.h; ++y) {
      const double dx = g.dx(win.y0 + y), dy = g.dy(win.y0 + y), diagonal = std::hypot(dx, dy);
      for (uint8_t d = 1; d <= 8; ++d)
        steps_[size_t(y) * 9 + d] = kDx[d] == 0 ? dy : kDy[d] == 0 ? dx : diagonal;
    }
    for (uint8_t d = 1; d <= 8; ++d)
      offset_[d] = kDy[d] * w_ + kDx[d];
  }

  // The neighbour of window cell (x, y) in direction d, or -1 (off the
  // window or no data).
  int64_t neighbour(int64_t x, int64_t y, int d) const {
    if (x > 0 && y > 0 && x < w_ - 1 && y < win_.h - 1) {  // inside: no bounds to check
      const int64_t n = y * w_ + x + offset_[d];
      return z_[size_t(n)] == kNoData ? -1 : n;
    }
    int64_t nx = x + kDx[d];
    const int64_t ny = y + kDy[d];
    if (ny < 0 || ny >= win_.h) return -1;
    if (nx < 0 || nx >= w_) {
      if (!win_.wraps) return -1;
      nx = (nx + w_) % w_;
    }
    const int64_t n = ny * w_ + nx;
    return z_[size_t(n)] == kNoData ? -1 : n;
  }

  // Water leaves the data here: the window's edge (not across the wrap) or
  // a cell next to no data.
  bool is_seed(int64_t x, int64_t y) const {
    if (y == 0 || y == win_.h - 1 || (!win_.wraps && (x == 0 || x == w_ - 1))) return true;
    for (int d = 1; d <= 8; ++d)
      if (neighbour(x, y, d) < 0) return true;
    return false;
  }

  // Per cell one byte, the state in the high nibble and the receiver code in
  // the low one (one cache line for both: the search waits on memory).
  void run(CarvedFlow& out, std::vector<uint32_t>& order) {
    const size_t cells = z_.size();
    std::vector<uint8_t>& cell = out.code;  // kNoDataCode, state kUnseen
    int32_t lowest = INT32_MAX, highest = INT32_MIN;
    size_t data = 0;
    for (int32_t v : z_)
      if (v != kNoData) lowest = std::min(lowest, v), highest = std::max(highest, v), ++data;
    if (data == 0) return;
    queue_.reset(lowest, highest, data);
    // Without holes only the window's edge holds seeds: no neighbour scan.
    const bool holes = data < cells;
    for (int64_t y = 0; y < win_.h; ++y)
      for (int64_t x = 0; x < w_; ++x) {
        const size_t i = size_t(y * w_ + x);
        const bool edge = y == 0 || y == win_.h - 1 || (!win_.wraps && (x == 0 || x == w_ - 1));
        if (z_[i] == kNoData || !(edge || (holes && is_seed(x, y)))) continue;
        cell[i] = pack(kSeed, kOutlet);
        queue_.push(z_[i], uint32_t(i));
      }
    order.reserve(data);
    while (!queue_.empty()) {
      const uint32_t i = queue_.pop();
      order.push_back(i);
      work(i, cell);
      cell[i] = pack(kWorked, code_of(cell[i]));
    }
    for (uint8_t& c : cell)
      c = code_of(c);
  }

 private:
  static uint8_t pack(uint8_t state, uint8_t code) { return uint8_t(state << 4 | code); }
  static uint8_t state_of(uint8_t c) { return c >> 4; }
  static uint8_t code_of(uint8_t c) { return c & 15; }

  // The ground distance from a cell of window row y to its neighbour d.
  double step(int64_t y, uint8_t d) const { return steps_[size_t(y) * 9 + d]; }

  void work(uint32_t i, std::vector<uint8_t>& cell) {
    const uint32_t row = i / uint32_t(w_);  // (a 32-bit division: this is the hot loop)
    const int64_t y = row, x = int64_t(i) - y * w_;
    const double dx = g_.dx(win_.y0 + y), dy = g_.dy(win_.y0 + y);
    const int32_t here = z_[i];
    int64_t at[9];
    double climb[9] = {0};  // to the neighbours not yet worked that lie higher
    for (uint8_t d = 1; d <= 8; ++d) {
      at[d] = neighbour(x, y, d);
      if (at[d] >= 0 && state_of(cell[size_t(at[d])]) != kWorked && z_[size_t(at[d])] > here)
        climb[d] = double(z_[size_t(at[d])] - here) / step(y, d);
    }
    for (uint8_t d : kOrder) {
      if (at[d] < 0) continue;
      const size_t n = size_t(at[d]);
      const uint8_t toward = d8_code(-kDx[d], -kDy[d]);
      switch (state_of(cell[n])) {
        case kSeed:  // still draining off the data: here, if lower
          if (here < z_[n]) cell[n] = pack(kQueued, toward);
          break;
        case kQueued:
          if (steeper_here(n, y + kDy[d], i, toward, cell)) cell[n] = pack(kQueued, toward);
          break;
        case kUnseen:
          if (yields(d, at, climb, dx, dy)) break;
          cell[n] = pack(kQueued, toward);
          queue_.push(z_[n], uint32_t(n));
          break;
        default:
          break;
      }
    }
  }

  // Whether queued cell n (of window row ny), now draining by its code,
  // should drain to worked cell i (in direction `toward` from n) instead:
  // the descent to i is steeper, or as steep and i drains off the data where
  // n's receiver does not (so a level strip along the data's edge drains
  // straight off it, not along it).
  bool steeper_here(size_t n, int64_t ny, uint32_t i, uint8_t toward,
                    const std::vector<uint8_t>& cell) const {
    const uint8_t now = code_of(cell[n]);
    const int64_t r = neighbour(int64_t(n) - ny * w_, ny, now);
    const double drop_here = double(z_[n] - z_[i]);
    if (r < 0) return drop_here > 0;  // (drains off the data: only for a descent)
    // drop_here / step_here against drop_now / step_now, without dividing.
    const double here = drop_here * step(ny, now),
                 now_ = double(z_[n] - z_[size_t(r)]) * step(ny, toward);
    return here > now_ ||
           (here == now_ && code_of(cell[i]) == kOutlet && code_of(cell[size_t(r)]) != kOutlet);
  }

  // Whether diagonal neighbour d is left to an orthogonal neighbour between:
  // one higher than this cell and not yet worked, from which the climb to
  // it is steeper than from here.
  bool yields(uint8_t d, const int64_t* at, const double* climb, double dx, double dy) const {
    if (d % 2 == 1 || climb[d] <= 0) return false;
    const int32_t target = z_[size_t(at[d])];
    const uint8_t same_row = kDy[d] < 0 ? 1 : 5;     // N or S: a step east or west to it
    const uint8_t same_column = kDx[d] > 0 ? 3 : 7;  // E or W: a step north or south to it
    for (const auto& [o, step] : {std::pair{same_row, dx}, std::pair{same_column, dy}}) {
      if (climb[o] <= 0) continue;
      const int32_t from = z_[size_t(at[o])];
      if (target > from && climb[d] < double(target - from) / step) return true;
    }
    return false;
  }

  const FlowGrid& g_;
  const GridWindow& win_;
  const std::vector<int32_t>& z_;
  const int64_t w_;
  std::vector<double> steps_;  // per window row, per direction: the ground distance
  int64_t offset_[9] = {0};    // per direction: the index step inside the window
  HeightQueue queue_;
};

}  // namespace

GridWindow GridWindow::of_tiles(const FlowGrid& g, const std::vector<tileformat::TileId>& finest) {
  GridWindow win;
  if (finest.empty()) return win;
  const int64_t steps = g.steps(), tiles_x = int64_t(g.tiling().tiles_x(g.zoom()));
  std::vector<int64_t> cols;
  int64_t row0 = INT64_MAX, row1 = -1;
  for (const tileformat::TileId& t : finest) {
    cols.push_back(int64_t(t.x));
    row0 = std::min<int64_t>(row0, t.y), row1 = std::max<int64_t>(row1, t.y);
  }
  std::sort(cols.begin(), cols.end());
  cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
  int64_t col0 = cols.front(), span = cols.back() - cols.front() + 1;
  if (g.wraps()) {
    // Leave out the widest run of empty columns, going round.
    int64_t gap = cols.front() + tiles_x - cols.back() - 1;
    for (size_t i = 1; i < cols.size(); ++i)
      if (cols[i] - cols[i - 1] - 1 > gap) {
        gap = cols[i] - cols[i - 1] - 1;
        col0 = cols[i];
      }
    span = tiles_x - gap;
  }
  win.y0 = row0 * steps;
  win.h = (row1 - row0 + 1) * steps + 1;
  win.x0 = col0 * steps;
  win.wraps = g.wraps() && span == tiles_x;
  win.w = win.wraps ? g.width() : span * steps + 1;
  return win;
}

CarvedFlow route_least_cost(const FlowGrid& g, const GridWindow& win,
                            const std::vector<int32_t>& z) {
  const uint64_t cells = win.cells();
  if (cells >= UINT32_MAX)
    throw std::length_error("least-cost routing: " + std::to_string(cells) +
                            " cells, more than it can index (2^32 - 1)");
  CarvedFlow out;
  out.code.assign(size_t(cells), kNoDataCode);
  std::vector<uint32_t> order;
  {
    Search search(g, win, z);
    search.run(out, order);
  }
  // Upstream areas: the search order is a topological order (a cell's
  // receiver was worked before it), so backwards each cell has its whole
  // inflow when it passes it on.
  out.area.assign(size_t(cells), 0);
  const int64_t w = win.w;
  for (int64_t y = 0; y < win.h; ++y)
    for (int64_t x = 0; x < w; ++x)
      if (z[size_t(y * w + x)] != kNoData) out.area[size_t(y * w + x)] = g.area_units(win.y0 + y);
  for (size_t k = order.size(); k-- > 0;) {
    const uint32_t i = order[k];
    const uint8_t c = out.code[i];
    if (c == kOutlet) continue;
    // The receiver: one index step, unless it crosses the window's wrap.
    const int64_t y = int64_t(i / uint32_t(w)), x = int64_t(i) - y * w, nx = x + kDx[c];
    const int64_t r = int64_t(i) + kDy[c] * w + kDx[c] + (nx < 0 ? w : nx >= w ? -w : 0);
    out.area[size_t(r)] += out.area[i];
  }
  return out;
}

}  // namespace globe::flow
