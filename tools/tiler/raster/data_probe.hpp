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

#include "raster_footprint.hpp"
#include "shard_plan.hpp"

namespace globe {

// `tiles`: the build's finest tiles (one zoom); `nodata`: per source, the
// value that means no data (NaN never counts as data). Work 1 (nodata) to 3
// (all valid), in integer units of 1/4.
std::vector<TileWork> probe_tile_work(const Footprint& footprint,
                                      const std::vector<RasterSource>& sources,
                                      const std::vector<std::optional<double>>& nodata,
                                      const std::vector<tileformat::TileId>& tiles);

}  // namespace globe
