// KPatch error trees (docs/terrain.md "Error trees"). All errors are in
// height quanta, rounded up. In lib/runtime because two writers of MBlocks
// share it: the tiler (tools/tiler/terrain) and the viewer, which
// synthesizes blocks from raster-DEM tiles (viewer/data/block_synthesizer).
// Pure arithmetic on tileformat's KPatch layout; touches nothing else.
//
// Node errors Ê(n): an upper bound of the vertical distance between node n
// drawn as its L x L lattice and the finest data under it, saturated so a
// node's error is >= its children's. At the finest zoom Ê(n) is exact
// (measured on the block's own samples); at coarser zooms nodes of depth >= 2
// take their value from the child block holding the same triangle, and the
// top two depths bound it as own deviation + max child error.
//
// Vertex errors e(v), stored in the MBlock: for the centre of a level-m cell,
// the max cell error over the 3 x 3 cells around it; for an edge midpoint, the
// max of its two nodes and of the vertex errors of the four sub-cells along
// the edge. This makes e saturated over the whole 4-8 vertex hierarchy
// (a vertex's error is >= each of its children's) and makes shared edge
// vertices identical in both blocks, because it reads neighbouring blocks.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "tileformat/kpatch.hpp"

namespace globe {

// children: node errors of the four child blocks in TileId::children() order,
// nullptr where the child has no block; all nullptr at the finest zoom.
std::vector<uint32_t> node_errors(const tileformat::KPatchLayout& layout,
                                  const std::vector<int32_t>& q, const std::vector<uint8_t>& valid,
                                  const std::array<const std::vector<uint32_t>*, 4>& children);

// nb[dy + 1][dx + 1]: node errors of the block at offset (dx, dy), nullptr if
// absent; nb[1][1] is the block itself.
using Neighbourhood = std::array<std::array<const std::vector<uint32_t>*, 3>, 3>;
std::vector<uint32_t> vertex_errors(const tileformat::KPatchLayout& layout,
                                    const Neighbourhood& nb);

// Exact max deviation (quanta) of node `index` drawn as its lattice from the
// valid samples under it; max_abs_q bounds |q| over the block (it picks the
// width of the arithmetic, not the result).
double lattice_deviation(const tileformat::KPatchLayout& layout, size_t index,
                         const std::vector<int32_t>& q, const std::vector<uint8_t>& valid,
                         int64_t max_abs_q);

}  // namespace globe
