// Flow direction and accumulation of a whole terrain package's finest zoom,
// out of core: the grid is cut into chunks sized to fit `memory_bytes`, each
// pass streams the chunks (in parallel) and keeps in memory only the chunks'
// perimeters and the small graphs that join them; per-cell intermediates go
// to scratch files next to the output. The same answer, bit for bit, for any
// chunk size and thread count (docs/analysis.md, "Flow"):
//   1. fill: per-chunk priority-flood with watershed labels (depression_fill)
//   2. spill levels of the watershed graph -> the filled heights
//   3. flats: distances to the nearest draining cell, iterated across chunks
//   4. depressions: searched from their entries; those crossing chunk edges
//      joined and gathered whole (depression_routing)
//   5. D8 receivers, per-chunk accumulation, perimeter links (flow_directions,
//      flow_accumulation)
//   6. the perimeter graph -> each chunk's inflow
//   7. final accumulation per chunk -> every zoom (flow_pyramid)
// Where the whole grid fits the budget as one chunk that does not wrap, the
// same passes run once on it, without the joining (1 and 2 as one flood with
// no watersheds), on one thread; --flow-chunk chooses chunks instead.
// FlowMethod::kCarve replaces 1-4 by least-cost routing of the whole grid in
// memory (least_cost_routing.hpp).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "analysis/flow/flow_grid.hpp"
#include "analysis/flow/flow_method.hpp"
#include "analysis/flow/flow_pyramid.hpp"
#include "kit/progress.hpp"
#include "runtime/terrain_package.hpp"

namespace globe::flow {

struct FlowSettings {
  FlowMethod method = FlowMethod::kFill;
  uint64_t memory_bytes = uint64_t(1024) << 20;
  int64_t chunk = 0;  // chunk side (a power of two); 0: chunk_size_for
  int threads = 1;
  std::string scratch_prefix;  // scratch files are this + a name
  std::string input;           // the terrain package's path, for messages
};

struct FlowSolution {
  std::unique_ptr<FlowGrid> grid;
  std::unique_ptr<FlowPyramid> pyramid;
  uint64_t watersheds = 0, perimeter_cells = 0;
  int flat_rounds = 0;
  bool scratch_in_memory = false;  // the per-cell scratch fitted the budget
  FlowMethod method = FlowMethod::kFill;
};

// The chunk size (a power of two): the whole grid as one chunk where it does
// not wrap and fits the budget; else, of those whose working set fits the
// budget, the one that processes the fewest cells (chunks are whole even
// where the data covers a corner; each decodes the tiles it touches), the
// largest of equals.
int64_t chunk_size_for(const tileformat::Tiling& tiling, int zoom, int block_size,
                       const std::vector<tileformat::TileId>& finest, uint64_t memory_bytes,
                       int threads);

// Throws InputError for a corrupt terrain block, OutputError for scratch
// files that cannot be written, UsageError where --flow-method carve's whole
// grid does not fit `memory_bytes`.
FlowSolution solve_flow(const TerrainPackage& package, const FlowSettings& settings,
                        Progress& progress);

}  // namespace globe::flow
