// Sky-view factor (Zakšek, Oštir & Kokalj 2011): the share of the sky a
// sample sees, 1 - mean over N azimuths of sin(horizon elevation), the
// horizon being the highest elevation angle of the terrain within a radius
// R. 1 on a plane or a peak, lower in valleys and pits: ambient occlusion.
// Pure arithmetic over a HeightWindow (the formulas: docs/analysis.md).
#pragma once

#include <vector>

#include "analysis/height_levels.hpp"
#include "analysis/terrain_derivatives.hpp"

namespace globe {

struct SkyViewSettings {
  int directions = 16;
  double radius_m = 10000;
};

// Where the rays of a block with `steps` samples a side and smallest ground
// spacing `min_spacing_m` find heights (HeightLevels): at its own zoom within
// a halo covering the radius, capped at two blocks; past that cap at the next
// coarser zoom (spacing doubled, again capped at two of its blocks), and so
// on until a level covers the radius or `coarser_zooms` run out.
struct SkyViewReach {
  std::vector<int> halos;  // per level: the block's own zoom, its parent's, ...
  double radius_m = 0;     // the radius every sample's rays reach: R, or less
};
SkyViewReach sky_view_reach(const SkyViewSettings& s, double min_spacing_m, int steps,
                            int coarser_zooms);

// The scan of one row of samples (one ground spacing): per direction, the
// sample offsets and ground distances of its steps, fine near the sample and
// growing geometrically further out.
class SkyViewScan {
 public:
  SkyViewScan(const SkyViewSettings& s, GroundSpacing spacing);
  // The factors of row y of the levels' block, x = 0 .. size - 1, into `out`
  // (NaN where the sample has no data). A ray moves to a coarser level where
  // a finer one's window ends, and stops at the first step whose bilinear
  // neighbourhood is not all valid data (HeightLevels::height) or past the
  // coarsest level. Each step is taken for the whole row at once in the
  // block's own zoom (the same offsets for every sample of the row: rows of
  // the window are read in order), one sample at a time past it.
  void row(const HeightLevels& levels, int y, int size, double* out) const;

 private:
  struct Step {
    double dx, dy, inv_distance;  // sample offsets, 1 / metres
    int ix, iy;                   // floor(dx), floor(dy)
    double tx, ty;                // dx - ix, dy - iy: the bilinear weights
  };
  std::vector<std::vector<Step>> rays_;
};

}  // namespace globe
