// Flow accumulation over the whole grid, chunk by chunk: the scheme of
// Barnes (2017, "Parallel non-divergent flow accumulation for trillion cell
// digital elevation models"). Each chunk accumulates its own cells' areas
// downstream and links every perimeter cell to the next perimeter cell its
// water reaches inside the chunk (or to the cell of another chunk it drains
// into). Solving that small graph of perimeter cells gives the water each
// chunk receives from outside; a second pass over each chunk adds it.
// Areas are integers (kAreaUnitsPerM2), so every order of summing is exact.
#pragma once

#include <cstdint>
#include <vector>

#include "analysis/flow/flow_grid.hpp"

namespace globe::flow {

inline constexpr int64_t kNoNode = -1;

// Per perimeter cell of one chunk (perimeter order).
struct PerimeterFlow {
  std::vector<uint64_t> area;   // upstream area from inside the chunk
  std::vector<int32_t> next;    // next perimeter cell downstream inside, or -1
  std::vector<uint8_t> leaves;  // drains straight into another chunk's cell
};

// Upstream areas of the chunk's cells: own area plus `inflow` (per perimeter
// cell, may be empty), summed downstream along `receivers` inside the chunk.
// `perimeter`, when given, receives the links described above; `leaves` is
// set where a receiver lies outside the chunk.
std::vector<uint64_t> accumulate_chunk(const FlowGrid& grid, const Chunk& chunk,
                                       const std::vector<uint8_t>& receivers,
                                       const std::vector<uint64_t>& inflow,
                                       PerimeterFlow* perimeter);

// The perimeter graph of all chunks: per node (perimeter cell) its upstream
// area from inside its chunk, its successor node (kNoNode: none) and whether
// the successor is in another chunk (the node's full area flows there) or
// downstream in its own (only what the node received from outside flows on:
// the rest is already in the successor's own-chunk area). Returns each
// node's inflow from other chunks.
std::vector<uint64_t> solve_inflows(const std::vector<uint64_t>& area,
                                    const std::vector<int64_t>& successor,
                                    const std::vector<uint8_t>& crosses);

}  // namespace globe::flow
