// Sky-view factor (Zakšek, Oštir & Kokalj 2011): the share of the sky a
// sample sees, 1 - mean over N azimuths of sin(horizon elevation), the
// horizon being the highest elevation angle of the terrain within a radius
// R. 1 on a plane or a peak, lower in valleys and pits: ambient occlusion.
// Pure arithmetic over a HeightWindow (the formulas: docs/analysis.md).
#pragma once

#include <vector>

#include "analysis/height_window.hpp"
#include "analysis/terrain_derivatives.hpp"

namespace globe {

struct SkyViewSettings {
  int directions = 16;
  double radius_m = 10000;
};

// The halo, in samples, a block with `steps` samples a side needs so that
// rays of radius_m at the finest ground spacing `min_spacing_m` stay inside
// the window: capped at two blocks (rays past it stop there: on DEMs finer
// than R / 512 samples, and east-west near the geodetic poles; docs/analysis.md).
int sky_view_halo(const SkyViewSettings& s, double min_spacing_m, int steps);

// The scan of one row of samples (one ground spacing): per direction, the
// sample offsets and ground distances of its steps, fine near the sample and
// growing geometrically further out.
class SkyViewScan {
 public:
  SkyViewScan(const SkyViewSettings& s, GroundSpacing spacing);
  // The factor at sample (x, y) of the window's block; rays stop at the
  // first step whose bilinear neighbourhood is not all valid data.
  double factor(const HeightWindow& w, int x, int y) const;

 private:
  struct Step {
    double dx, dy, inv_distance;  // sample offsets, 1 / metres
  };
  std::vector<std::vector<Step>> rays_;
};

}  // namespace globe
