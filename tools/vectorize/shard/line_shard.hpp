// Sharded line builds (docs/scale-out.md): which features and tiles are one
// shard's. A line tile depends only on the features that reach it, not on
// its children, so every tile of every zoom can be built by any shard and
// shards need no data from each other. Feature ids, the zoom range and a
// local tiling are the whole build's, though: every shard reads (and
// numbers) all features and plans as one machine would. The work is shared
// out as subtrees below the split zoom and, above it, single coarse tiles
// (each on the Morton curve before the first subtree it covers). A shard
// cuts a feature only at the zooms where it reaches one of its tiles, and
// keeps only its tiles.
#pragma once

#include <cstdint>

#include "io/geometry_scratch.hpp"
#include "kit/progress.hpp"
#include "kit/shard_plan.hpp"
#include "lines/line_plan.hpp"
#include "lines/lines_settings.hpp"

namespace globe {

class LineShard {
 public:
  // Plans shard s.shard of the build `plan` from the `features` features in
  // `scratch` (read through twice and rewound). Work estimate: the vertices
  // under a tile, counted at a probe zoom (the finest zoom, at most 10, or
  // --split-zoom), times the zooms a subtree spans. Subtrees and coarse
  // tiles: every tile a feature's bounding box may reach, also where none of
  // its vertices lie. Throws UsageError for a bad --split-zoom.
  LineShard(const LinesSettings& s, const LinePlan& plan, GeometryScratch& scratch,
            uint64_t features, Progress& progress);

  const ShardPlan& plan() const { return plan_; }
  // The zooms at which the shard cuts `f` (bit z set for zoom z): those
  // where f's bounding box, widened by the zoom's reach (from the split zoom
  // on: the farthest reach of those zooms), touches one of the shard's tiles.
  uint32_t zooms_to_cut(const ProjectedFeature& f) const;
  // Whether tile `id` is the shard's to write.
  bool keeps(tileformat::TileId id) const { return plan_.contains(id); }

 private:
  // The tiles of zoom z that f's bounding box `b`, widened by `reach`
  // (tiling CRS units), touches.
  tileformat::TileRange reached(const tileformat::Bounds& b, int z) const;
  // Whether one of the shard's tiles of zoom z (its subtree roots at the
  // split zoom) lies in r.
  bool owns_any(const tileformat::TileRange& r, int z) const;
  const LinePlan& lines_;
  ShardPlan plan_;
  // Per zoom: how far the cutter's tile boxes reach past the tile (tiling
  // CRS units); at the split zoom, the farthest of the zooms from it on.
  std::vector<double> reach_crs_;
};

}  // namespace globe
