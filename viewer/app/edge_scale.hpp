// The edges shading's stretch, per zoom: the plan curvature times the sample
// spacing (the change of grade across the slope per sample) at which ridge
// and valley colours saturate, the 95th percentile of its magnitude over the
// first 64 k samples of that zoom's blocks (in load order), so that a gentle
// plateau and a sharp range both show their ridges and valleys, and every
// zoom looks alike although curvature grows with the spacing.
#pragma once

#include <array>
#include <vector>

#include "data/block_cache.hpp"

namespace globe::viewer {

class EdgeScale {
 public:
  static constexpr int kZooms = 32;
  // spacing_m: ground metres between the block's samples. True when a
  // zoom's stretch changed.
  bool add_samples(const LoadedBlock& block, double spacing_m);
  // Per zoom; a zoom without samples takes the nearest one's; 0.05 without
  // any (no analysis package, or no curvature layer).
  std::array<float, kZooms> scales() const;

 private:
  std::array<std::vector<float>, kZooms> samples_;
  std::array<float, kZooms> scale_{};  // 0: none yet
};

}  // namespace globe::viewer
