// Label placement (see label_placement.hpp).
#include "app/label_placement.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace globe::viewer {

// Boxes placed so far, bucketed by the grid cells they touch.
class LabelPlacer::Grid {
 public:
  Grid(const LabelPlacementOptions& o)
      : cell_(o.cell_px),
        x0_(-o.padding_px),
        y0_(-o.padding_px),
        cols_(std::max(1, int(std::ceil((float(o.width) + 2 * o.padding_px) / o.cell_px)))),
        rows_(std::max(1, int(std::ceil((float(o.height) + 2 * o.padding_px) / o.cell_px)))),
        cells_(size_t(cols_) * size_t(rows_)) {}

  bool free(const std::vector<ScreenBox>& boxes) const {
    for (const ScreenBox& b : boxes) {
      const auto [c0, r0, c1, r1] = span(b);
      for (int r = r0; r <= r1; ++r)
        for (int c = c0; c <= c1; ++c)
          for (uint32_t i : cells_[size_t(r) * size_t(cols_) + size_t(c)])
            if (boxes_[i].overlaps(b)) return false;
    }
    return true;
  }
  void insert(const std::vector<ScreenBox>& boxes) {
    for (const ScreenBox& b : boxes) {
      const auto i = static_cast<uint32_t>(boxes_.size());
      boxes_.push_back(b);
      const auto [c0, r0, c1, r1] = span(b);
      for (int r = r0; r <= r1; ++r)
        for (int c = c0; c <= c1; ++c)
          cells_[size_t(r) * size_t(cols_) + size_t(c)].push_back(i);
    }
  }

 private:
  struct Span {
    int c0, r0, c1, r1;
  };
  Span span(const ScreenBox& b) const {
    auto col = [&](float x) {
      return std::clamp(int(std::floor((x - x0_) / cell_)), 0, cols_ - 1);
    };
    auto row = [&](float y) {
      return std::clamp(int(std::floor((y - y0_) / cell_)), 0, rows_ - 1);
    };
    return {col(b.x0), row(b.y0), col(b.x1), row(b.y1)};
  }
  float cell_, x0_, y0_;
  int cols_, rows_;
  std::vector<std::vector<uint32_t>> cells_;
  std::vector<ScreenBox> boxes_;
};

namespace {

std::vector<ScreenBox> shifted(const std::vector<ScreenBox>& boxes, BoxShift s) {
  std::vector<ScreenBox> out = boxes;
  for (ScreenBox& b : out)
    b = {b.x0 + s.dx, b.y0 + s.dy, b.x1 + s.dx, b.y1 + s.dy};
  return out;
}

}  // namespace

std::vector<LabelPlace> LabelPlacer::place(const std::vector<LabelBid>& bids, double dt_s,
                                           bool still, int max_new,
                                           const std::vector<ScreenBox>& obstacles) {
  ++frame_;
  tried_ = shown_ = 0;
  // Shown labels first (they keep their place), then by priority, then key.
  std::vector<uint32_t> order(bids.size());
  std::iota(order.begin(), order.end(), 0u);
  std::vector<char> was_shown(bids.size());
  for (size_t i = 0; i < bids.size(); ++i) {
    auto it = state_.find(bids[i].key);
    was_shown[i] = it != state_.end() && it->second.shown && it->second.seen + 1 == frame_;
  }
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    if (was_shown[a] != was_shown[b]) return was_shown[a] > was_shown[b];
    if (bids[a].priority != bids[b].priority) return bids[a].priority > bids[b].priority;
    return bids[a].key < bids[b].key;
  });
  Grid grid(o_);
  grid.insert(obstacles);
  std::vector<LabelPlace> out(bids.size());
  const float step = still ? 1.f : static_cast<float>(std::clamp(dt_s, 0.0, 1.0) * o_.fade_per_s);
  int tried_new = 0;
  // The first of the bid's places (last frame's first) that terrain leaves
  // clear and no label placed so far covers; -1 for none.
  // A label that is not shown yet needs room around it too (a margin of
  // half its height, at most 8 px) unless the camera stands still: then the
  // small moves of the next frames do not push it off again (no off-on-off).
  auto fit = [&](const LabelBid& b, int preferred, bool appearing, std::vector<ScreenBox>& boxes) {
    const int n = static_cast<int>(b.shifts.size());
    std::vector<ScreenBox> roomy;
    for (int k = -1; k < n; ++k) {
      const int s = k < 0 ? preferred : k;
      if (s < 0 || s >= n || (k >= 0 && s == preferred)) continue;
      if (!b.clear.empty() && !b.clear[size_t(s)]) continue;
      boxes = shifted(b.boxes, b.shifts[size_t(s)]);
      if (appearing) {
        roomy = boxes;
        for (ScreenBox& r : roomy) {
          const float m = std::min(o_.appear_margin * (r.y1 - r.y0), o_.appear_margin_max_px);
          r = {r.x0 - m, r.y0 - m, r.x1 + m, r.y1 + m};
        }
      }
      if (grid.free(appearing ? roomy : boxes)) return s;
    }
    return -1;
  };
  std::vector<ScreenBox> boxes;
  for (uint32_t i : order) {
    const LabelBid& b = bids[i];
    State& s = state_[b.key];
    if (s.seen + 1 != frame_) s = State{};  // not bid last frame: starts afresh
    s.seen = frame_;
    if (!b.drawable) {  // behind terrain or out of view: gone at once
      s.alpha = 0, s.fits = 0, s.shown = false;
      continue;
    }
    if (s.shown) {
      const int at = fit(b, s.shift, false, boxes);
      if (at < 0) {  // pushed off by a label shown before it
        s.alpha = 0, s.fits = 0, s.shown = false;
        continue;
      }
      ++tried_;
      grid.insert(boxes);
      s.shift = at;
      if (b.legible) {
        s.alpha = std::min(1.f, s.alpha + step);
      } else {  // too small: fades out, keeping its place meanwhile
        s.alpha = std::max(0.f, s.alpha - step);
        if (s.alpha <= 0) s.shown = false, s.fits = 0;
      }
      out[i] = {s.alpha, s.shift};
      if (s.alpha > 0) ++shown_;
      continue;
    }
    if (!b.legible) {
      s.fits = 0;
      continue;
    }
    if (max_new >= 0 && tried_new >= max_new) continue;  // deferred (keeps its streak)
    ++tried_new, ++tried_;
    const int at = fit(b, s.fits > 0 ? s.shift : 0, !still, boxes);
    if (at < 0) {
      s.fits = 0;
      continue;
    }
    ++s.fits;
    s.shift = at;
    // Its room is kept even before it shows, so that the next frame can show it.
    grid.insert(boxes);
    if (!still && s.fits < o_.frames_to_show) continue;
    s.shown = true;
    s.alpha = std::min(1.f, still ? 1.f : s.alpha + step);
    out[i] = {s.alpha, s.shift};
    ++shown_;
  }
  // Labels that bid no more are forgotten.
  for (auto it = state_.begin(); it != state_.end();)
    it = it->second.seen == frame_ ? std::next(it) : state_.erase(it);
  return out;
}

}  // namespace globe::viewer
