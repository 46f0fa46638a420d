// Depression filling over the whole grid, chunk by chunk: the tiled
// priority-flood of Barnes (2016, "Parallel priority-flood depression
// filling for trillion cell digital elevation models"). Each chunk floods
// from its own perimeter and from the cells next to no data (which drain off
// the data), labelling every cell with the watershed it was reached from and
// noting the lowest spill between touching watersheds. A small graph of
// watersheds (within chunks, and across chunk edges) then gives each
// watershed the level it must be raised to: filled = max(local fill, that
// level). The result is the unique priority-flood filling of the whole grid.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "analysis/flow/chunk_heights.hpp"

namespace globe::flow {

// Watershed labels within a chunk: 1 drains to the data's edge inside the
// chunk; 2.. watersheds that reach the chunk's perimeter.
inline constexpr uint32_t kEdgeLabel = 1;

struct SpillEdge {
  uint32_t a, b;  // labels, a < b
  int32_t level;  // the lowest height over which one spills into the other
};

// The lowest spill noted per pair of labels (in a chunk's flood, or across
// chunk edges), then as edges sorted by label pair.
class SpillPairs {
 public:
  void note(uint32_t a, uint32_t b, int32_t level);
  void clear() { lowest_.clear(); }
  void append_to(std::vector<SpillEdge>& edges) const;

 private:
  std::unordered_map<uint64_t, int32_t> lowest_;  // key: a << 32 | b, a < b
};

struct ChunkFill {
  // The chunk's window (ChunkWindow), the ring left as kNoData and 0.
  std::vector<int32_t> filled;   // kNoData where no data
  std::vector<uint32_t> label;   // 0 where no data
  uint32_t labels = 2;           // labels used: 1 .. labels - 1
  std::vector<SpillEdge> edges;  // lowest spill per pair of labels
};

// `heights`: the chunk's window (chunk_heights).
ChunkFill fill_chunk(const Chunk& chunk, const std::vector<int32_t>& heights);

// fill_chunk's filled heights alone, without watersheds: the final surface
// of a chunk that is the whole grid (nothing drains in from outside it).
std::vector<int32_t> filled_surface(const Chunk& chunk, const std::vector<int32_t>& heights);

// The level each watershed of the global graph must be raised to; node 0 is
// the data's edge (its level is kNoData, i.e. below everything). Nodes no
// edge reaches keep kNoData.
std::vector<int32_t> spill_levels(size_t nodes, const std::vector<SpillEdge>& edges);

// A window cell next to no data (its own cell has data): water leaves there.
inline bool at_data_edge(const std::vector<int32_t>& window, size_t k, int stride) {
  const size_t s = size_t(stride);
  return window[k - s - 1] == kNoData || window[k - s] == kNoData || window[k - s + 1] == kNoData ||
         window[k - 1] == kNoData || window[k + 1] == kNoData || window[k + s - 1] == kNoData ||
         window[k + s] == kNoData || window[k + s + 1] == kNoData;
}

}  // namespace globe::flow
