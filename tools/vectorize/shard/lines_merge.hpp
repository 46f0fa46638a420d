// Merging line or area shards (docs/scale-out.md) into the package one
// machine builds from the same command. A line or area tile depends only on
// the features that reach it, so each shard cut its tiles exactly (its
// subtrees and its share of the tiles above the split zoom), and shard 0
// holds the whole features table.
// The merge copies that table, then the tiles in the one-machine order
// (coarsest zoom first). Resumable like a build.
#pragma once

#include "kit/build_options.hpp"
#include "kit/progress.hpp"
#include "kit/shard_set.hpp"
#include "lines/lines_builder.hpp"

namespace globe {

// o: output, force, resume, command line (inputs: the shards; line or area
// shards, ShardSet::kind()). Fills the summary's tile, feature, zoom and size
// counts.
LinesSummary merge_lines(ShardSet& shards, const BuildOptions& o, Progress& progress);

}  // namespace globe
