// The kinds of intermediate data the raster builders (terrain, imagery) keep
// in their staging store (tileformat/staging_store.hpp), one table per stage
// and zoom.
#pragma once

#include "tileformat/staging_store.hpp"

namespace globe {

using tileformat::StageCheckpoint;
using tileformat::StagingStore;

// kRaw: a block's own samples (imagery: a tile's pixels); kEdges: just its
// first row and column (what its west/north neighbours take from it);
// kFinal / kNodeErrors / kQuarter (every other sample, for the parent):
// after terrain's pass 2.
struct Stage {
  enum : tileformat::StageTag { kRaw = 1, kFinal = 2, kNodeErrors = 3, kEdges = 4, kQuarter = 5 };
};

}  // namespace globe
