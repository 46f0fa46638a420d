// Per-zoom values measured from the blocks loaded so far (app/edge_scale,
// app/relief_scale): a zoom not measured yet takes the nearest measured
// zoom's value (finer first at equal distance: the coarser one wins only when
// nearer), or `none` while nothing is measured.
#pragma once

#include <array>

namespace globe::viewer {

template <size_t N>
std::array<float, N> nearest_measured(const std::array<float, N>& measured, float none) {
  std::array<float, N> out;
  for (int z = 0; z < int(N); ++z) {
    out[z] = none;
    for (int d = 0; d < int(N); ++d) {
      if (z - d >= 0 && measured[z - d] > 0) {
        out[z] = measured[z - d];
        break;
      }
      if (z + d < int(N) && measured[z + d] > 0) {
        out[z] = measured[z + d];
        break;
      }
    }
  }
  return out;
}

}  // namespace globe::viewer
