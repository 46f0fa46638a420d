// The hillshade's relief stretch per zoom (docs/viewer.md "Readable by
// default"): on coarse grids the slopes between samples are gentle (a 9 km
// grid's Himalaya rises a few degrees per sample) and the hillshade comes out
// a flat grey. Each zoom's stretch multiplies the heights' slopes for the
// lighting only (not the geometry, nor the slope and aspect modes) so that
// its 90th-percentile slope reads as kTargetSlope; never below 1 (detailed
// data keeps its look), at most kMaxStretch. Measured from the blocks as they
// load, like the edges' stretch (edge_scale.hpp).
#pragma once

#include <array>
#include <vector>

#include "data/block_cache.hpp"

namespace globe::viewer {

class ReliefScale {
 public:
  static constexpr int kZooms = 32;
  static constexpr float kTargetSlope = 0.3f;  // rise over run, about 17 degrees
  static constexpr float kMaxStretch = 12.0f;

  // spacing_x_m, spacing_y_m: ground metres between the block's samples east
  // and south. True when a zoom's stretch changed.
  bool add_samples(const LoadedBlock& block, double spacing_x_m, double spacing_y_m);
  // Per zoom (1 = none); a zoom without samples takes the nearest one's.
  std::array<float, kZooms> stretches() const;

 private:
  std::array<std::vector<float>, kZooms> slopes_;
  std::array<float, kZooms> stretch_{};  // 0: none yet
};

}  // namespace globe::viewer
