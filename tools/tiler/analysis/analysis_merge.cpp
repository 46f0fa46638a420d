// Analysis shard merge (see analysis_merge.hpp).
#include "analysis/analysis_merge.hpp"

#include <chrono>

#include "kit/package_output.hpp"
#include "runtime/package_open.hpp"
#include "tileformat/error.hpp"
#include "tileformat/metadata.hpp"

namespace globe {

AnalysisSummary merge_analysis(ShardSet& shards, const BuildOptions& o, Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  const tileformat::AnalysisMetadata meta = read_metadata(
      shards.path(0), [&] { return tileformat::read_analysis_metadata(shards.metadata()); });
  const tileformat::ShardMetadata shard = *tileformat::read_shard_metadata(shards.metadata());
  AnalysisSummary sum;
  std::unique_ptr<tileformat::PackageWriter> writer = create_package(o, progress);
  write_package_tiles(o.output, [&] {
    shards.copy_tiles(*writer, shard.min_zoom, meta.common.max_zoom, progress);
  });
  if (writer->tiles_written() == 0)
    throw InputError("the shards hold no tiles; nothing written to " + o.output);
  writer->set_metadata(shards.merged_metadata(o.output, shard.min_zoom, o.command_line));
  commit_package(*writer, o.output, start, sum);
  return sum;
}

}  // namespace globe
