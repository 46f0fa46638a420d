// Passes 2 and 3 of a line-cluster build (lines_builder.hpp), shared by every
// builder that writes line tiles (lines, bundles): the projected features of
// a scratch file are cut into the tiles of their zooms and sorted by tile
// (cut_line_tiles), then each tile gets its cluster grid and is encoded and
// written in key order (encode_line_tiles). Parallel work is done in batches
// consumed in order, so output is identical for any thread count.
#pragma once

#include <cstdint>
#include <functional>

#include "io/geometry_scratch.hpp"
#include "kit/progress.hpp"
#include "lines/line_plan.hpp"
#include "tileformat/package.hpp"
#include "tiles/tile_cutter.hpp"
#include "tiles/tile_sorter.hpp"

namespace globe {

struct LineTileOptions {
  int extent = 4096, cluster_grid = 32;
  double simplify_px = 0.25;
  int threads = 1;
  // Zooms to cut a feature at (bit z), on top of the feature's own
  // ProjectedFeature::zooms; none: every zoom of the plan.
  std::function<uint32_t(const ProjectedFeature&)> zooms;
  // Tiles to keep (a shard's); none: every tile.
  std::function<bool(tileformat::TileId)> keeps;
};

struct LineTileStats {
  CutStats cut;
  uint64_t segments = 0, max_zoom_segments = 0, points = 0;
};

// Cuts the `features` features of `scratch` (read from its start) into
// `sorter`, then finishes it.
void cut_line_tiles(GeometryScratch& scratch, uint64_t features, const LinePlan& plan,
                    const LineTileOptions& o, TileSorter& sorter, LineTileStats& stats,
                    Progress& progress);

// Encodes the sorted tiles and puts them in `writer` (a resumed package's
// tiles, which come first in key order, are skipped).
void encode_line_tiles(TileSorter& sorter, const LinePlan& plan, const LineTileOptions& o,
                       tileformat::PackageWriter& writer, LineTileStats& stats, Progress& progress);

}  // namespace globe
