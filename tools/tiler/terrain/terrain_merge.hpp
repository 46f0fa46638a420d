// Merging terrain shards (docs/scale-out.md) into the package one machine
// builds from the same command: zooms from the finest to the split zoom are
// the shards' tiles, in the whole build's order; tiles next to another
// shard's get their vertex errors again from the node errors of all their
// neighbours (the shard tables hold those near each border); the zooms above
// the split zoom are built by the terrain builder's own passes from the
// split zoom's quarters and node errors. Resumable like a build.
#pragma once

#include "kit/build_options.hpp"
#include "kit/progress.hpp"
#include "kit/shard_set.hpp"
#include "terrain/terrain_builder.hpp"

namespace globe {

// o: output, force, resume, threads, command line (inputs: the shards).
BuildSummary merge_terrain(ShardSet& shards, const BuildOptions& o, Progress& progress);

}  // namespace globe
