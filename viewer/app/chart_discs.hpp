// The charts of a frame on screen (docs/labels.md, step 3): the discs no
// label covers, and the radius of the chart at a place, which its label
// keeps clear of. Bucketed by 64 px cells for the lookups.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "app/label_placement.hpp"

namespace globe::viewer {

class ChartDiscs {
 public:
  void add(float x, float y, float radius_px);
  // The radius of the largest chart covering pixel (x, y), 0 for none.
  float radius_at(float x, float y) const;
  // Each disc's square of 0.8 of its radius around its centre: what
  // labels may not cover (the pie's rim may be overlapped by a label's
  // corner, its body not).
  std::vector<ScreenBox> obstacles() const;

 private:
  struct Disc {
    float x, y, r;
  };
  static int64_t cell(float x, float y);
  std::vector<Disc> discs_;
  std::unordered_map<int64_t, std::vector<uint32_t>> cells_;
};

}  // namespace globe::viewer
