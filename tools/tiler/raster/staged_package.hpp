// The envelope of the raster builds and merges (terrain, imagery): the
// package (created, or a resumed build's) with its staging store beside it,
// and a shard's table. Each builder writes its levels inside; the envelope
// owns the order in which they are opened and closed.
#pragma once

#include <memory>
#include <optional>

#include "kit/build_options.hpp"
#include "kit/package_output.hpp"
#include "kit/progress.hpp"
#include "kit/shard_plan.hpp"
#include "raster/raster_stages.hpp"
#include "tileformat/package.hpp"
#include "tileformat/shard_table.hpp"

namespace globe {

// Creates the package for o.output (or continues a resumed build's) and its
// staging store (continued with it), runs write(writer, stage) with failed
// writes reported as OutputErrors naming the output (write_package_tiles),
// and returns the writer with its tiles written, not yet committed.
template <class Write>
std::unique_ptr<tileformat::PackageWriter> write_staged_package(const BuildOptions& o,
                                                                Progress& progress, Write&& write) {
  std::unique_ptr<tileformat::PackageWriter> writer = create_package(o, progress);
  write_package_tiles(o.output, [&] {
    StagingStore stage(
        o.output + ".staging", writer->key_hash(),
        writer->resumed() ? tileformat::Resume::kContinue : tileformat::Resume::kStartAfresh);
    write(*writer, stage);  // (the store's statements end before the writer closes the file)
  });
  return writer;
}

// Runs write(parts): for a shard, parts is its shard table, holding its
// roots (tileformat/shard_table.hpp), open while write runs; else nullptr.
template <class Write>
void with_shard_table(tileformat::PackageWriter& writer, const ShardPlan* shard, Write&& write) {
  std::optional<tileformat::ShardTableWriter> parts;
  if (shard) {
    parts.emplace(writer);
    parts->put_roots(shard->roots);
  }
  write(parts ? &*parts : nullptr);
}

}  // namespace globe
