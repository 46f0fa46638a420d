// Builds a terrain package from a plan (docs/terrain.md "Pipeline"). For each
// zoom from the finest up, three passes over the level's tiles:
//   1. raw:    finest zoom: warp the sources onto the tile's samples;
//              coarser: take every other sample of the four children (valid
//              samples only), so coarse samples equal fine ones.
//   2. final:  a block's last column/row come from its east/south neighbours
//              (one owner per shared sample), holes are filled, node errors
//              are computed and the MBlock is encoded (heights and mask).
//   3. encode: vertex errors from the 3 x 3 neighbourhood are spliced into
//              that MBlock, which is written to the package.
// Intermediate blocks live in a scratch SQLite file; parallel work is done in
// batches and consumed in tile order, so output is identical for any -j.
#pragma once

#include "kit/package_output.hpp"

#include <cstdint>

#include "kit/progress.hpp"
#include "raster/raster_stages.hpp"
#include "terrain/dem_plan.hpp"
#include "terrain/terrain_settings.hpp"
#include "tileformat/package.hpp"

namespace globe {

struct BuildSummary : PackageSummary {
  uint64_t samples = 0;  // samples stored (tiles * size^2)
};

// The whole build, or with settings.shard one shard of it: the subtrees
// below the split zoom that fall to it, warping the first row and column of
// the tiles just east and south of them (the halo, from the inputs), plus
// the shard table (tileformat/shard_table.hpp) the merge needs: node errors
// near the shard's border and at the split zoom, the split zoom's quarters.
// A shard's tiles on its border carry vertex errors that ignore the other
// shards; the merge recomputes them.
BuildSummary build_terrain(const DemPlan& plan, const TerrainSettings& settings,
                           Progress& progress);

// The merge's share (terrain_merge.hpp): zooms `top` down to plan.min_zoom
// into `writer`, from a stage holding level top + 1's final blocks
// (Stage::kFinal, any bytes: only listed), node errors and quarters; resumes
// from the stage's checkpoint when the writer was resumed. Returns the
// coarsest zoom written.
int build_terrain_levels(const DemPlan& plan, const TerrainSettings& settings,
                         tileformat::PackageWriter& writer, StagingStore& stage, int top,
                         Progress& progress);

}  // namespace globe
