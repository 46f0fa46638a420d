// A stand-in for a terrain block that cannot be read (issue 55: three broken
// tiles at the top of a global package blanked the whole globe). Samples are
// nested across zooms (docs/terrain.md: a coarse sample is the fine sample at
// the same position), so a block is remade from its four children by taking
// every other sample — exact where they hold data — and, where it has no
// children (the finest zoom), from its parent by bilinear interpolation.
// A child that is broken too is remade from its own children, one level
// further; a quadrant with no data stays a hole (masked), so a hole is never
// larger than the broken tile's footprint at the finest zoom that has data.
// Runs on the loader thread, reading through the package's reader.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tileformat/tile_id.hpp"

namespace globe::viewer {

// Per-sample values of one block, `channels` floats a sample, row-major from
// the north row, and a mask (255 data, 0 hole).
struct SampleGrid {
  int size = 0, channels = 1;
  std::vector<float> values;
  std::vector<uint8_t> mask;
};

enum class Stand { kNone, kChildren, kParent };

struct SubstituteSource {
  int block_size = 0, min_zoom = 0, max_zoom = 0;
  // The tile's grid, nullopt if the package has no such tile; throws if the
  // tile is there but cannot be read.
  std::function<std::optional<SampleGrid>(tileformat::TileId)> read;
};

// The stand-in for `id` and where it came from (kNone: nothing to make it
// from). Children come first, the parent where there are none.
std::pair<std::optional<SampleGrid>, Stand> substitute_grid(const SubstituteSource& source,
                                                            tileformat::TileId id);

// The grid of four children's every-other samples (one per quadrant; a
// missing child leaves its quadrant masked), and the quadrant (qx, qy) of a
// parent's grid interpolated to full size. Exposed for tests.
SampleGrid from_children(const std::optional<SampleGrid> (&children)[2][2], int size, int channels);
SampleGrid from_parent(const SampleGrid& parent, int qx, int qy);

}  // namespace globe::viewer
