// Aggregating places for coarser zooms (docs/points.md "Aggregation"): the
// places of one zoom merge into the places of the next coarser zoom, where
// places closer than a radius become one. Greedy in a fixed order (the
// heaviest place first, then the smallest id), so the result never depends
// on thread count or input order: the first place not yet taken takes every
// other untaken place within the radius of it; the merged place sits at
// their weighted centre and carries the sums of their values and counts and
// the smallest of their ids (summed in id order). Zooms are built from the
// next finer one, so zooming in splits a chart into the charts it was made
// of. On the global tilings distances wrap around the antimeridian.
//
// The merge streams: places arrive in horizontal bands, north to south, at
// least a radius high (so places two bands apart are never neighbours), and
// only the bands still undecided stay in memory. The greedy's outcome is
// local: a place is a centre exactly when no heavier neighbour is a centre,
// and otherwise belongs to its heaviest neighbouring centre; a place is
// decided once its heavier neighbours are, and a centre is emitted once its
// neighbours are decided. Chains of ever heavier neighbours can hold bands
// back; on real places they are short.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <unordered_map>
#include <vector>

#include "points/place_stream.hpp"

namespace globe {

// Where distances wrap: the CRS width once around the Earth (the global
// tilings; 0 for none) and the west edge x.
struct Wrap {
  double width = 0, west = 0;
};

// Places of a sliding window bucketed into square cells of at least the
// radius (columns wrap on the global tilings), so a place's neighbours within
// the radius lie in the 3 x 3 cells around its own. Places are numbered in
// the order they are added and leave in that order.
class CellWindow {
 public:
  CellWindow(double radius, Wrap wrap);
  // Adds place number `seq` (the next number) at (x, y).
  void add(uint64_t seq, double x, double y);
  // Forgets every place numbered below `seq`.
  void drop_before(uint64_t seq);
  // Calls fn(seq) for every place in the cells around (x, y).
  template <typename Fn>
  void near(double x, double y, Fn fn) const {
    const int64_t cx = column(x), cy = row(y);
    int64_t seen[3] = {INT64_MIN, INT64_MIN, INT64_MIN};
    for (int dx = -1; dx <= 1; ++dx) {
      int64_t c = cx + dx;
      if (columns_ > 0) c = ((c % columns_) + columns_) % columns_;
      if (c == seen[0] || c == seen[1]) continue;  // few columns: each once
      seen[dx + 1] = c;
      for (int64_t r = cy - 1; r <= cy + 1; ++r) {
        auto it = cells_.find(key(c, r));
        if (it == cells_.end()) continue;
        for (uint64_t s : it->second)
          fn(s);
      }
    }
  }
  // Whether b lies within the radius of a (the short way round on the
  // global tilings); the same answer both ways.
  bool within(double ax, double ay, double bx, double by) const {
    const double ddx = dx(ax, bx), ddy = by - ay;
    return ddx * ddx + ddy * ddy <= r2_;
  }
  // x offset from a to b, the short way round on the global tilings.
  double dx(double a, double b) const {
    double d = b - a;
    if (wrap_.width > 0) {
      if (d > wrap_.width / 2) d -= wrap_.width;
      if (d < -wrap_.width / 2) d += wrap_.width;
    }
    return d;
  }

 private:
  int64_t column(double x) const;
  int64_t row(double y) const;
  static uint64_t key(int64_t c, int64_t r) {
    return (static_cast<uint64_t>(c) << 32) ^ (static_cast<uint64_t>(r) & 0xffffffffu);
  }
  Wrap wrap_;
  double r2_;
  double size_x_, size_y_;
  int64_t columns_ = 0;        // > 0: columns wrap
  uint64_t first_ = 0;         // the oldest place's number
  std::deque<uint64_t> keys_;  // each place's cell, oldest first
  std::unordered_map<uint64_t, std::vector<uint64_t>> cells_;
};

// Merges the places of one zoom into those of the next coarser one, band by
// band; `emit` receives each merged place (in no particular order: callers
// sort them).
class BandMerger {
 public:
  BandMerger(double radius, Wrap wrap, std::function<void(const Place&)> emit);
  // The places of the next band, north to south (bands increase; places two
  // bands apart must lie farther apart than the radius).
  void add_band(int64_t band, std::vector<Place>&& places);
  // After the last band: decides and emits the rest.
  void finish();
  // The most places held at once (for --stats and the bench).
  size_t peak_places() const { return peak_; }

 private:
  enum class State : uint8_t { kUndecided, kCentre, kMember };
  struct Slot {
    Place place;
    double weight;
    int64_t band;
    State state = State::kUndecided;
    uint64_t owner = 0;  // a member's centre
  };
  Slot& slot(uint64_t seq) { return slots_[seq - first_]; }
  const Slot& slot(uint64_t seq) const { return slots_[seq - first_]; }
  // Whether a ranks before b in the merge order.
  static bool before(const Slot& a, const Slot& b) {
    return a.weight != b.weight ? a.weight > b.weight : a.place.id < b.place.id;
  }
  void decide(int64_t below_band);
  void emit_centre(uint64_t seq);
  void emit_and_drop(int64_t decided_through);

  CellWindow cells_;
  Wrap wrap_;
  std::function<void(const Place&)> emit_;
  std::deque<Slot> slots_;
  uint64_t first_ = 0;      // number of slots_[0]
  uint64_t next_emit_ = 0;  // the first slot not yet looked at for emitting
  std::vector<uint64_t> undecided_;
  int64_t last_band_ = INT64_MIN;
  size_t peak_ = 0;
  std::vector<uint64_t> members_;
};

// The share of places (read in sweep order from `places`) that have another
// place within `radius`: what merging at that radius would touch (for
// choosing the finest zoom). `band` gives a place's band, 0 or more (as for
// BandMerger).
double crowded_share(PlaceSource& places, double radius, Wrap wrap,
                     const std::function<int64_t(const Place&)>& band);

}  // namespace globe
