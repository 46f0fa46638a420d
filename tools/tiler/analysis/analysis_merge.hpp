// Merging analysis shards (docs/scale-out.md) into the package one machine
// builds from the same command. Every analysis block reads only the terrain
// package, so shards computed theirs exactly and shard 0 also the zooms above
// the split zoom: the merge copies tiles, in the one-machine order (coarsest
// zoom first). Resumable like a build.
#pragma once

#include "analysis/analysis_builder.hpp"
#include "kit/build_options.hpp"
#include "kit/progress.hpp"
#include "kit/shard_set.hpp"

namespace globe {

// o: output, force, resume, command line (inputs: the shards).
AnalysisSummary merge_analysis(ShardSet& shards, const BuildOptions& o, Progress& progress);

}  // namespace globe
