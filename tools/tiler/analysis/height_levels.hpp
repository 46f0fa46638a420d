// A block's heights at its own zoom and, for what lies further out, around
// its ancestors at coarser zooms: level k is the HeightWindow of the
// ancestor k zooms up with its own halo, so each level reaches about twice
// as far as the one before with as many samples (the far field of the
// thesis's RASTeR ambient occlusion). Every level is addressed in the
// block's own sample coordinates. Pure memory work, no I/O.
#pragma once

#include <cmath>
#include <vector>

#include "analysis/height_window.hpp"

namespace globe {

class HeightLevels {
 public:
  // halos[k]: the halo of level k, in samples of its zoom; halos.size()
  // levels, at most id.z + 1.
  HeightLevels(const tileformat::Tiling& tiling, tileformat::TileId id, int size,
               const std::vector<int>& halos, const BlockLookup& block);
  // The tiles the levels read, each once.
  static std::vector<tileformat::TileId> tiles(const tileformat::Tiling& tiling,
                                               tileformat::TileId id, int size,
                                               const std::vector<int>& halos);

  const HeightWindow& own() const { return levels_[0].window; }

  enum class Sample { kHeight, kNoData, kOutside };
  // The height at (fx, fy), in the block's sample coordinates, interpolated
  // bilinearly in level `level` or, where that level's window ends, in the
  // first coarser one that holds the point (`level` moves there). kNoData
  // where a corner has no data (in a coarser zoom the data's edge is up to
  // one of its samples further in); kOutside past the coarsest level.
  Sample height(double fx, double fy, int& level, double& h) const {
    for (; level < int(levels_.size()); ++level) {
      const Level& l = levels_[size_t(level)];
      const double cx = (fx + l.offset_x) * l.scale, cy = (fy + l.offset_y) * l.scale;
      const double x0 = std::floor(cx), y0 = std::floor(cy);
      const int ix = static_cast<int>(x0), iy = static_cast<int>(y0);
      const HeightWindow& w = l.window;
      if (!w.inside(ix, iy) || !w.inside(ix + 1, iy + 1)) continue;
      if (!w.valid(ix, iy) || !w.valid(ix + 1, iy) || !w.valid(ix, iy + 1) ||
          !w.valid(ix + 1, iy + 1))
        return Sample::kNoData;
      const double tx = cx - x0, ty = cy - y0;
      const double top = w.height(ix, iy) + tx * (w.height(ix + 1, iy) - w.height(ix, iy));
      const double bottom =
          w.height(ix, iy + 1) + tx * (w.height(ix + 1, iy + 1) - w.height(ix, iy + 1));
      h = top + ty * (bottom - top);
      return Sample::kHeight;
    }
    return Sample::kOutside;
  }

 private:
  struct Level {
    HeightWindow window;
    double offset_x, offset_y;  // the block's origin in the ancestor, block samples
    double scale;               // ancestor samples per block sample: 2^-k
  };
  std::vector<Level> levels_;
};

}  // namespace globe
