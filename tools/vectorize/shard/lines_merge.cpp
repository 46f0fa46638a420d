// Line shard merge (see lines_merge.hpp).
#include "shard/lines_merge.hpp"

#include <chrono>

#include "kit/package_output.hpp"
#include "runtime/package_open.hpp"
#include "tileformat/error.hpp"
#include "tileformat/feature_table.hpp"
#include "tileformat/label_table.hpp"
#include "tileformat/metadata.hpp"

namespace globe {

LinesSummary merge_lines(ShardSet& shards, const BuildOptions& o, Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  // The keys both kinds have: the zooms and the features.
  struct {
    tileformat::CommonMetadata common;
    uint64_t features = 0;
  } meta;
  if (shards.kind() == tileformat::PackageKind::kAreas) {
    const auto m = read_metadata(shards.path(0),
                                 [&] { return tileformat::read_area_metadata(shards.metadata()); });
    meta = {m.common, m.features};
  } else {
    const auto m = read_metadata(shards.path(0),
                                 [&] { return tileformat::read_line_metadata(shards.metadata()); });
    meta = {m.common, m.features};
  }
  const tileformat::ShardMetadata shard = *tileformat::read_shard_metadata(shards.metadata());
  LinesSummary sum;
  std::unique_ptr<tileformat::PackageWriter> writer = create_package(o, progress);
  try {
    write_package_tiles(o.output, [&] {
      // As in a build: the features table in the first transaction, committed
      // before any tile (a resumed merge finds it complete).
      tileformat::FeatureTableWriter features(*writer);
      if (!features.complete()) {
        tileformat::FeatureTableReader from(shards.reader(0));
        progress.begin("copy features", static_cast<uint64_t>(from.count()));
        from.for_each([&](int64_t id, const tileformat::FeatureRecord& f) {
          features.add(id, f.layer, f.properties);
          progress.advance();
        });
        progress.end();
      }
      // Shard 0's labels (it names every feature, as it holds the features).
      if (tileformat::has_labels(shards.reader(0))) {
        tileformat::LabelTableWriter labels(*writer);
        if (!labels.complete())
          tileformat::LabelTableReader(shards.reader(0))
              .for_each([&](const tileformat::LabelRecord& l) { labels.add(l); });
      }
      writer->checkpoint();
      shards.copy_tiles(*writer, shard.min_zoom, meta.common.max_zoom, progress);
    });
  } catch (const tileformat::FormatError& e) {
    throw InputError(shards.path(0) + ": " + e.what());
  }
  writer->set_metadata(shards.merged_metadata(o.output, shard.min_zoom, o.command_line));
  sum.features_kept = meta.features;
  sum.min_zoom = shard.min_zoom;
  sum.max_zoom = meta.common.max_zoom;
  commit_package(*writer, o.output, start, sum);
  return sum;
}

}  // namespace globe
