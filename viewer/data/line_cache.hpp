// Line-cluster tiles on their way from a package to the GPU, within a memory
// budget (data/arena_tile_cache.hpp does the caching): each tile decoded into
// the words the line shader reads (tile_words layout below). Tiles the
// package does not have show no lines; the shader draws the coarser tiles
// over broken ones, or where there are none the finer tiles under them
// (issue 55).
//
// Tile words (all u32): cell offsets (C*C + 1, relative to the cell list),
// the cell list (segment indices), then 6 words per segment: ax, ay, bx, by
// (tile units as float bits), class id, distance along the run at a (units,
// float bits; for dashes). The segments are in the tile's run order, so a
// segment index names its run, and the run its feature.
//
// Highlighting (picking in the viewer): the runs of a chosen set of features
// take one more class, drawn over the others; changing the set reloads the
// resident tiles.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "data/arena_tile_cache.hpp"
#include "runtime/line_package.hpp"
#include "tileformat/line_tile.hpp"

namespace globe::viewer {

inline constexpr uint32_t kLineWordsPerSegment = 6;

// What the loader makes of a blob.
struct DecodedLineTile {
  uint32_t extent = 0, grid = 0, reach = 0, segments = 0, cell_entries = 0;
  float longest = 0;  // the longest segment, in tile units
  std::vector<uint32_t> words;
};

// Features drawn in their own class instead of their runs' classes.
struct LineHighlight {
  std::vector<uint64_t> features;  // sorted feature ids
  uint32_t class_id = 0;
};

// Turns a decoded tile into its GPU words (exposed for tests); the runs of
// highlighted features get the highlight's class.
DecodedLineTile line_tile_words(const tileformat::LineTile& tile,
                                const LineHighlight* highlight = nullptr);

// The feature id of segment `segment` of the tile (in line_tile_words'
// order), or nullopt past its segments.
std::optional<uint64_t> segment_feature(const tileformat::LineTile& tile, uint32_t segment);

using LineRecord = ArenaRecord<DecodedLineTile>;
using LineCacheStats = ArenaCacheStats;

class LineCache final : public ArenaTileCache<DecodedLineTile> {
 public:
  LineCache(const std::string& path, LinePackage package, uint64_t budget_bytes);
  ~LineCache() override;

  const LinePackage& package() const { return package_; }
  // Draws these features in `highlight.class_id` from now on (none: empty
  // features): waits for the loader and forgets every tile, which the next
  // frames load again.
  void set_highlight(LineHighlight highlight);

 private:
  LinePackage package_;
  std::mutex highlight_mutex_;  // the loader thread reads highlight_
  std::shared_ptr<const LineHighlight> highlight_;
};

}  // namespace globe::viewer
