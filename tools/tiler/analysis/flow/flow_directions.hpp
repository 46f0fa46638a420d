// D8 flow directions on the filled heights of one chunk (with the ring of
// cells around it from its neighbours). A cell with a lower neighbour drains
// to the steepest one (drop over true ground distance; ties to the first in
// N, NE, E .. NW order). A cell next to no data without a lower neighbour is
// an outlet. The rest lie on flats (filled depressions, level ground): each
// drains towards the nearest cell of its flat that can drain (the distance
// counted in D8 steps within the flat), so water crosses a flat by the
// shortest way; of the neighbours one step nearer it takes the one whose way
// off the flat leads lowest (the least key: a draining cell's key is the
// height of its lowest lower neighbour), as a search in height order (GRASS
// r.watershed's) would. Flats may span chunks: the distances and keys of the
// ring come from the neighbouring chunks and are iterated to a fixed point by
// the solver.
#pragma once

#include <cstdint>
#include <vector>

#include "analysis/flow/chunk_heights.hpp"

namespace globe::flow {

inline constexpr uint32_t kFar = UINT32_MAX;  // no known way off the flat yet
inline constexpr int32_t kNoKey = INT32_MAX;  // no known key yet

// `filled`: the chunk's window of filled heights. `distance` and `key`: the
// window's ring holds the neighbours' (0 off a flat, kFar unknown; kNoKey);
// the chunk's cells are computed: distance 0 where the cell is not on a flat,
// else D8 steps to the nearest cell off the flat (through the ring as well);
// key as above (for a cell next to no data without a lower neighbour, its
// own height).
void flat_distances(const Chunk& chunk, const std::vector<int32_t>& filled,
                    std::vector<uint32_t>& distance, std::vector<int32_t>& key);

// flat_distances in two steps. classify_flats: distance 0 and the key of
// every cell off a flat, kFar and kNoKey on one; returns the flat cells.
// settle_flats: the distances and keys of `flats` (window indices, at kFar
// and kNoKey, whole flats: every flat cell next to one of them at its height
// is listed too) from the known cells around them.
std::vector<uint32_t> classify_flats(const Chunk& chunk, const std::vector<int32_t>& filled,
                                     std::vector<uint32_t>& distance, std::vector<int32_t>& key);
void settle_flats(const Chunk& chunk, const std::vector<int32_t>& filled,
                  std::vector<uint32_t>& distance, std::vector<int32_t>& key,
                  const std::vector<uint32_t>& flats);

// The chunk's flat cells (distance not 0) of every flat that touches a ring
// cell of its height flagged in `changed` (window-indexed): the flats whose
// distances and keys a change of those ring cells can alter. Each flat once.
std::vector<uint32_t> flats_next_to(const Chunk& chunk, const std::vector<int32_t>& filled,
                                    const std::vector<uint32_t>& distance,
                                    const std::vector<uint8_t>& changed);

// Receiver codes of the chunk's cells (w * h; kNoDataCode where no data).
std::vector<uint8_t> d8_receivers(const FlowGrid& grid, const Chunk& chunk,
                                  const std::vector<int32_t>& filled,
                                  const std::vector<uint32_t>& distance,
                                  const std::vector<int32_t>& key);

}  // namespace globe::flow
