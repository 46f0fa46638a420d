// Analysis shard merge (see analysis_merge.hpp).
#include "analysis_merge.hpp"

#include <chrono>

#include "package_open.hpp"
#include "package_output.hpp"
#include "tileformat/error.hpp"
#include "tileformat/metadata.hpp"

namespace globe {

using tileformat::TileId;

AnalysisSummary merge_analysis(ShardSet& shards, const BuildOptions& o, Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  const tileformat::AnalysisMetadata meta = read_metadata(
      shards.path(0), [&] { return tileformat::read_analysis_metadata(shards.metadata()); });
  const tileformat::ShardMetadata shard = *tileformat::read_shard_metadata(shards.metadata());
  AnalysisSummary sum;
  std::unique_ptr<tileformat::PackageWriter> writer = create_package(o, progress);
  try {
    for (int z = shard.min_zoom; z <= meta.common.max_zoom; ++z) {
      const std::vector<TileId> tiles = shards.tiles(z);
      const size_t done = writer->resumed() ? writer->tiles_at_zoom(z) : 0;
      progress.begin("z" + std::to_string(z) + " merge", tiles.size());
      for (size_t i = 0; i < tiles.size(); ++i) {
        if (i > 0 && tiles[i] == tiles[i - 1])
          throw InputError("tile " + tiles[i].str() + " is in two shards; the shards overlap");
        // Above the split zoom, shard 0 holds every tile.
        const int owner = z < shards.split_zoom() ? 0 : shards.owner(tiles[i]);
        auto blob = owner < 0 ? std::nullopt : shards.reader(owner).tile(tiles[i]);
        if (!blob)
          throw InputError("tile " + tiles[i].str() +
                           " is not where the shards' subtrees put it; the shards do not come "
                           "from one build");
        if (i >= done) writer->put_tile(tiles[i], *blob);
        progress.advance();
      }
      progress.end();
      writer->checkpoint();
    }
  } catch (const tileformat::PackageError& e) {
    throw build_write_error(o.output, e);
  }
  if (writer->tiles_written() == 0)
    throw InputError("the shards hold no tiles; nothing written to " + o.output);
  writer->set_metadata(shards.merged_metadata(o.output, shard.min_zoom, o.command_line));
  sum.tiles = writer->tiles_written();
  sum.unique_blobs = writer->unique_blobs();
  sum.file_bytes = commit_package(*writer, o.output);
  sum.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sum;
}

}  // namespace globe
