// Hole filling for block geometry (docs/terrain.md "Holes"): the tiler's
// blocks and the viewer's blocks made from remote elevation tiles
// (viewer/data/block_synthesizer) fill alike. Samples without
// data keep valid = 0 in the mask but need a height for the mesh. The fill
// must give identical values on an edge shared by two blocks, so it depends
// only on what both blocks see:
//   1. a corner without data gets the package's fill height;
//   2. an edge sample without data is interpolated linearly between the
//      nearest samples with a height on the same edge (corners included);
//   3. interior holes are filled inwards, wave by wave, each sample taking
//      the rounded mean of its already-known 4-neighbours.
#pragma once

#include <cstdint>
#include <vector>

namespace globe {

// q: size*size heights (quanta); valid: 1 = data. Modifies q at holes only.
void fill_holes(std::vector<int32_t>& q, const std::vector<uint8_t>& valid, int size,
                int32_t fill_q);

}  // namespace globe
