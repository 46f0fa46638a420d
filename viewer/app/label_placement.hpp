// Which labels a frame shows (docs/viewer.md "Labels"): a collision grid
// over the screen (MapLibre's: 25 px cells, 100 px of padding around the
// view, so that labels partly off screen still count), a priority order that
// keeps the labels already shown first (so a moving camera does not swap
// them for others), and per label a state with hysteresis: a label appears
// only after it has fitted in two frames in a row (never off-on-off), fades
// in, and is hidden at once when it no longer may be drawn (behind terrain,
// out of view, overlapped by a label shown before it) - a fade-out only where
// it shrank below the legibility cutoff, keeping its boxes meanwhile. Pure
// CPU; no GL.
#pragma once

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace globe::viewer {

struct ScreenBox {
  float x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // pixels from the top-left
  bool overlaps(const ScreenBox& o) const {
    return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1;
  }
};

// A shift of a label's boxes: one of the places it may go (a point label
// right, left, above or below its place).
struct BoxShift {
  float dx = 0, dy = 0;
};

// A label's bid for this frame.
struct LabelBid {
  uint64_t key = 0;              // stable across frames (which label, which repetition)
  double priority = 0;           // larger first
  std::vector<ScreenBox> boxes;  // what it covers (a line label: one per glyph)
  // Where it may go, in order of preference (the one it took last frame is
  // tried first); `clear`: per shift, whether terrain leaves it visible there
  // (empty: everywhere).
  std::vector<BoxShift> shifts = {BoxShift{}};
  std::vector<char> clear;
  // May be drawn at all: anchor in view and not behind terrain (decided by
  // the caller, with its own hysteresis).
  bool drawable = false;
  // Large enough to read; false with `drawable`: fades out, keeping its boxes.
  bool legible = true;
};

// What a frame decided for one bid.
struct LabelPlace {
  float alpha = 0;  // 0: not drawn
  int shift = 0;    // index into the bid's shifts
};

struct LabelPlacementOptions {
  int width = 0, height = 0;
  float cell_px = 25, padding_px = 100;
  float fade_per_s = 5;  // alpha change per second (0.2 s a fade)
  int frames_to_show = 2;
  // The room a label not shown yet needs around it: this fraction of its
  // boxes' height, at most appear_margin_max_px.
  float appear_margin = 0.5f, appear_margin_max_px = 8;
};

class LabelPlacer {
 public:
  explicit LabelPlacer(const LabelPlacementOptions& o) : o_(o) {}
  void set_size(int width, int height) { o_.width = width, o_.height = height; }

  // Decides this frame's labels among `bids` and returns each one's alpha
  // (0: not drawn) and place, in the order of `bids`. dt_s: seconds since
  // the last frame; still: a picture of a still camera (a snapshot): labels
  // that fit show at once and at full opacity. max_new: how many labels not
  // shown before are tried this frame (the placement budget; the rest wait
  // for the next frame), -1 for all. obstacles: what no label may cover
  // (the charts).
  std::vector<LabelPlace> place(const std::vector<LabelBid>& bids, double dt_s, bool still,
                                int max_new = -1, const std::vector<ScreenBox>& obstacles = {});
  // Forgets every label's state (labels toggled off).
  void reset() { state_.clear(); }
  // Of the last place(): bids tried and shown.
  size_t tried() const { return tried_; }
  size_t shown() const { return shown_; }

 private:
  struct State {
    float alpha = 0;
    int fits = 0;        // frames in a row it fitted while hidden
    bool shown = false;  // shown (fading in or full)
    uint32_t seen = 0;   // the frame it last bid in
    int shift = 0;       // where it went
  };
  class Grid;
  LabelPlacementOptions o_;
  std::unordered_map<uint64_t, State> state_;
  uint32_t frame_ = 0;
  size_t tried_ = 0, shown_ = 0;
};

}  // namespace globe::viewer
