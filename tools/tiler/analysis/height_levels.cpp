// A block's heights at its own and coarser zooms (see height_levels.hpp).
#include "analysis/height_levels.hpp"

#include <set>

namespace globe {
namespace {

using tileformat::TileId;

TileId ancestor(TileId id, int k) {
  return TileId{id.z - k, id.x >> k, id.y >> k};
}

}  // namespace

HeightLevels::HeightLevels(const tileformat::Tiling& tiling, TileId id, int size,
                           const std::vector<int>& halos, const BlockLookup& block) {
  const int n = size - 1;
  for (size_t k = 0; k < halos.size() && int(k) <= id.z; ++k) {
    const uint32_t below = (uint32_t{1} << k) - 1;  // the block's place among the ancestor's
    levels_.push_back(Level{HeightWindow(tiling, ancestor(id, int(k)), size, halos[k], block),
                            double(id.x & below) * n, double(id.y & below) * n,
                            1.0 / double(uint64_t{1} << k)});
  }
}

std::vector<TileId> HeightLevels::tiles(const tileformat::Tiling& tiling, TileId id, int size,
                                        const std::vector<int>& halos) {
  std::vector<TileId> out;
  std::set<TileId> seen;
  for (size_t k = 0; k < halos.size() && int(k) <= id.z; ++k)
    for (const TileId& t :
         tiles_around(tiling, ancestor(id, int(k)), HeightWindow::radius_for(size, halos[k])))
      if (seen.insert(t).second) out.push_back(t);
  return out;
}

}  // namespace globe
