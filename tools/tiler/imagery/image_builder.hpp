// Builds an image package from a plan (docs/imagery.md "Pipeline"). The
// finest zoom is warped from the sources in blocks of up to 4 x 4 tiles;
// every coarser zoom is built from its children's pixels (image_pyramid),
// never from the sources again. Pixels of the level below live in a scratch
// SQLite file (zstd), so memory does not grow with the input. Empty tiles
// are not written, identical tiles are stored once; parallel work is done in
// batches consumed in tile order, so output is identical for any -j.
#pragma once

#include "kit/package_output.hpp"

#include <cstdint>

#include "imagery/image_plan.hpp"
#include "kit/progress.hpp"
#include "raster/raster_stages.hpp"
#include "tileformat/package.hpp"
#include "tileformat/shard_table.hpp"

namespace globe {

struct ImageSummary : PackageSummary {
  uint64_t png = 0, jpeg = 0, webp = 0;  // tiles per encoding
};

// The part of an image shard's table (tileformat/shard_table.hpp) the merge
// builds the zooms above the split zoom from: each split-zoom tile's pixels
// as staged (zstd planes).
inline constexpr tileformat::ShardPartTag kShardPixels = 1;

// The whole build, or with settings.shard one shard of it: the subtrees
// below the split zoom that fall to it (image tiles do not depend on their
// neighbours: no halo), plus the split zoom's pixels in the shard table.
ImageSummary build_imagery(const ImagePlan& plan, const ImageSettings& settings,
                           Progress& progress);

// The merge's share: zooms `top` down to plan.min_zoom into `writer` from a
// stage holding level top + 1's pixels (Stage::kRaw); resumes from the
// stage's checkpoint when the writer was resumed.
struct ImageLevels {
  int coarsest = 0;
  ImageSummary formats;  // png, jpeg, webp: tiles written per encoding
};
ImageLevels build_imagery_levels(const ImagePlan& plan, const ImageSettings& settings,
                                 tileformat::PackageWriter& writer, StagingStore& stage, int top,
                                 Progress& progress);

}  // namespace globe
