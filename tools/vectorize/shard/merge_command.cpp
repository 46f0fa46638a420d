// `globe-vectorize merge SHARD... -o OUT.mbtiles`: joins the shards of one
// sharded line build (`globe-vectorize lines --shard I/N`) into the package
// one machine would build (docs/scale-out.md).
#include <sstream>

#include "kit/shard_set.hpp"
#include "runtime/cli_args.hpp"
#include "runtime/errors.hpp"
#include "shard/lines_merge.hpp"
#include "vectorize_commands.hpp"

namespace globe {

int run_lines_merge(const std::vector<std::string>& args) {
  BuildOptions o;
  CliArgs cli("globe-vectorize merge",
              "globe-vectorize merge SHARD... -o OUT.mbtiles [options]\n\n"
              "Joins the N shards of a line or area build run with --shard 0/N ... N-1/N (for\n"
              "example a Slurm array job, docs/scale-out.md) into the package the same command\n"
              "builds on one machine: the same tiles, features and metadata (only\n"
              "globe:command_line differs). Checks that the shards come from one build and cover\n"
              "it exactly once.");
  if (!parse_merge_command(cli, o, args, "globe-vectorize merge")) return kExitOk;

  Progress progress(o.progress);
  ShardSet shards(o.inputs);
  if (shards.kind() != tileformat::PackageKind::kLines &&
      shards.kind() != tileformat::PackageKind::kAreas)
    throw InputError(shards.path(0) + ": a " + tileformat::package_kind_name(shards.kind()) +
                     " shard; globe-vectorize merge joins line and area shards (the others: "
                     "globe-tiler merge)");
  progress.note("globe-vectorize: merging " + std::to_string(shards.count()) + " " +
                tileformat::package_kind_name(shards.kind()) + " shards split below zoom " +
                std::to_string(shards.split_zoom()));
  const LinesSummary sum = merge_lines(shards, o, progress);
  std::ostringstream out;
  out.precision(3);
  out << std::fixed << "globe-vectorize: wrote " << o.output << ": " << sum.features_kept
      << " features, zoom " << sum.min_zoom << ".." << sum.max_zoom << ", " << sum.tiles
      << " tiles (" << sum.unique_blobs << " unique), " << sum.file_bytes << " bytes, "
      << sum.seconds << " s";
  progress.note(out.str());
  return kExitOk;
}

}  // namespace globe
