// `globe-tiler merge SHARD... -o OUT.mbtiles`: joins the shards of one
// sharded build (`--shard I/N`) into the package one machine would build
// (docs/scale-out.md), by the shards' kind.
#include <sstream>

#include "analysis/analysis_merge.hpp"
#include "imagery/image_merge.hpp"
#include "kit/shard_set.hpp"
#include "runtime/cli_args.hpp"
#include "runtime/errors.hpp"
#include "terrain/terrain_merge.hpp"
#include "tiler_commands.hpp"

namespace globe {

int run_merge(const std::vector<std::string>& args) {
  BuildOptions o;
  CliArgs cli("globe-tiler merge",
              "globe-tiler merge SHARD... -o OUT.mbtiles [options]\n\n"
              "Joins the N shards of a build run with --shard 0/N ... N-1/N (for example a Slurm\n"
              "array job, docs/scale-out.md) into the package the same command builds on one\n"
              "machine: the same tiles and metadata (only globe:command_line differs). Checks\n"
              "that the shards come from one build and cover it exactly once, and builds the\n"
              "zooms above the split zoom. Terrain, imagery and analysis shards.");
  if (!parse_merge_command(cli, o, args, "globe-tiler merge")) return kExitOk;

  Progress progress(o.progress);
  ShardSet shards(o.inputs);
  const tileformat::PackageKind kind = shards.kind();
  if (kind == tileformat::PackageKind::kLines)
    throw InputError(shards.path(0) + ": a " + tileformat::package_kind_name(kind) +
                     " shard; globe-tiler merge joins terrain, imagery and analysis shards "
                     "(line shards: globe-vectorize merge)");
  progress.note("globe-tiler: merging " + std::to_string(shards.count()) + " " +
                tileformat::package_kind_name(kind) + " shards split below zoom " +
                std::to_string(shards.split_zoom()));
  uint64_t tiles = 0, unique = 0, bytes = 0;
  double seconds = 0;
  if (kind == tileformat::PackageKind::kTerrain) {
    const BuildSummary sum = merge_terrain(shards, o, progress);
    tiles = sum.tiles, unique = sum.unique_blobs, bytes = sum.file_bytes, seconds = sum.seconds;
  } else if (kind == tileformat::PackageKind::kImage) {
    const ImageSummary sum = merge_imagery(shards, o, progress);
    tiles = sum.tiles, unique = sum.unique_blobs, bytes = sum.file_bytes, seconds = sum.seconds;
  } else {
    const AnalysisSummary sum = merge_analysis(shards, o, progress);
    tiles = sum.tiles, unique = sum.unique_blobs, bytes = sum.file_bytes, seconds = sum.seconds;
  }
  std::ostringstream out;
  out.precision(3);
  out << std::fixed << "globe-tiler: wrote " << o.output << ": " << tiles << " tiles (" << unique
      << " unique), " << bytes << " bytes, " << seconds << " s";
  progress.note(out.str());
  return kExitOk;
}

}  // namespace globe
