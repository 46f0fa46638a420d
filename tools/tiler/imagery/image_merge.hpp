// Merging image shards (docs/scale-out.md) into the package one machine
// builds from the same command: zooms from the finest to the split zoom are
// the shards' tiles (image tiles do not depend on their neighbours); the
// zooms above are built by the image builder's own pyramid pass from the
// split zoom's pixels in the shard tables. Resumable like a build.
#pragma once

#include "imagery/image_builder.hpp"
#include "kit/build_options.hpp"
#include "kit/progress.hpp"
#include "kit/shard_set.hpp"

namespace globe {

// o: output, force, resume, threads, command line (inputs: the shards).
ImageSummary merge_imagery(ShardSet& shards, const BuildOptions& o, Progress& progress);

}  // namespace globe
