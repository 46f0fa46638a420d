// How much work each finest tile of a raster build is, for sharing a build
// out (kit/shard_plan.hpp): tiles over valid data cost about three times
// tiles inside the inputs' footprint that hold only nodata (measured:
// bench/shards.sh). Which tiles hold data comes from a coarse read of each
// input (at most 512 x 512 pixels, nearest; from overviews when the file has
// them), every probe pixel placed in the tiling; a tile takes the valid share
// of the probe pixels in its ancestor at the coarsest zoom where a tile gets
// at least 16 of them.
#pragma once

#include <optional>
#include <vector>

#include "kit/shard_plan.hpp"
#include "raster/raster_footprint.hpp"

namespace globe {

// Which band of a source says where it has data: a value band with its
// nodata value (the file's own when not given; NaN never counts as data),
// or an alpha band (0 = none).
struct ProbeBand {
  int band = 1;
  bool alpha = false;
  std::optional<double> nodata;
};

// `tiles`: the build's finest tiles (one zoom); `bands`: one per source.
// Work 1 (nodata) to 3 (all valid), in integer units of 1/4.
std::vector<TileWork> probe_tile_work(const Footprint& footprint,
                                      const std::vector<RasterSource>& sources,
                                      const std::vector<ProbeBand>& bands,
                                      const std::vector<tileformat::TileId>& tiles);

// Shard o.shard of a raster build: its finest tiles (those over the data
// areas) weighed by the probe, cut by plan_shard; notes its summary.
ShardPlan plan_raster_shard(const Footprint& footprint, const std::vector<RasterSource>& sources,
                            const std::vector<ProbeBand>& bands, const BuildOptions& o,
                            Progress& progress);

}  // namespace globe
