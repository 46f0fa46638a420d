// Flow at every zoom. The finest zoom is the solved grid; each coarser
// sample takes, of the finest cells in its footprint (the 2^k x 2^k cells
// from it east- and southwards), the one with the largest upstream area: its
// area, and as direction the coarser neighbour whose footprint holds that
// cell's receiver. That cell is where the footprint's largest river leaves
// it (its receiver has a larger area, so it lies outside), so coarse
// directions trace the fine rivers and rivers stay continuous at every zoom
// (network-tracing upscaling). Levels nest, so each is made from the one
// below by 2 x 2 maxima. Levels no coarser than a chunk are kept per chunk in
// scratch files (or in memory, as the solver's scratch); coarser ones (a few
// samples per chunk) in memory.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "analysis/flow/flow_grid.hpp"
#include "kit/scratch_array_file.hpp"

namespace globe::flow {

struct LevelShape {
  int64_t width = 0, height = 0;
  bool wraps = false;
};
// Level `factor` (cells per sample side, a power of two).
LevelShape level_shape(const FlowGrid& grid, int64_t factor);

// A rectangle of one level's samples.
struct LevelGrid {
  int64_t x0 = 0, y0 = 0;
  int w = 0, h = 0;
  std::vector<uint64_t> area;  // area units; 0 where no data
  std::vector<uint8_t> code;   // receiver codes; kNoDataCode where no data
};

// The next coarser level over the same cells (x0 and y0 even).
LevelGrid coarsen(const LevelGrid& child, const LevelShape& child_shape,
                  const LevelShape& parent_shape);

class FlowPyramid {
 public:
  // Zooms min_zoom .. grid.zoom(); scratch files at `scratch_prefix` + name,
  // or in memory.
  FlowPyramid(const FlowGrid& grid, int min_zoom, const std::string& scratch_prefix,
              bool in_memory);

  // A chunk's finest cells (x0, y0, w, h of the chunk); any thread.
  void put_chunk(int slot, LevelGrid finest);
  // After every chunk: the levels coarser than a chunk.
  void finish();

  // The samples of a tile (size x size, row-major): area units (0 none) and
  // receiver codes. Any thread.
  void block(tileformat::TileId id, int size, std::vector<uint64_t>& area,
             std::vector<uint8_t>& code) const;

 private:
  // A chunk's samples of a level kept per chunk, and where they are stored.
  struct Part {
    int64_t x0, y0;
    int w, h;
  };
  Part part(int level, int slot) const;
  uint64_t offset(int level, int slot) const { return offsets_[size_t(level)][size_t(slot)]; }

  const FlowGrid& grid_;
  int levels_;     // zooms: grid.zoom() - levels_ + 1 .. grid.zoom()
  int in_chunks_;  // levels 0 .. in_chunks_ - 1 kept per chunk (level k: factor 2^k)
  std::vector<std::vector<uint64_t>> offsets_;            // per chunk level, per slot
  std::vector<std::unique_ptr<ScratchArrayFile>> files_;  // per chunk level, on disk
  std::vector<std::vector<LevelGrid>> held_;              // or in memory: per chunk level, per slot
  std::vector<LevelGrid> tops_;                           // per slot: its coarsest chunk level
  std::vector<LevelGrid> coarse_;                         // levels in_chunks_ .. levels_ - 1, whole
  std::mutex mutex_;
};

}  // namespace globe::flow
