// The shards a merge joins (docs/scale-out.md): each opened once, checked to
// come from one build (same globe:shard_build, shard count and split zoom),
// each index given exactly once, and their subtrees disjoint and together
// the whole build's; then which shard holds each subtree and tile.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tileformat/package.hpp"
#include "tileformat/shard_table.hpp"

namespace globe {

class CliArgs;
class Progress;
struct BuildOptions;

// A merge command's options (-o, the run options) and its shards: parses
// `args` into `o` (false after --help) and refuses an output that is one of
// the shards (UsageError).
bool parse_merge_command(CliArgs& cli, BuildOptions& o, const std::vector<std::string>& args,
                         const std::string& program);

class ShardSet {
 public:
  // Throws InputError naming the file (and shard) that is missing, not a
  // shard, of another build or kind, given twice, or overlapping another;
  // or naming the shard index no file holds.
  explicit ShardSet(const std::vector<std::string>& paths);
  ~ShardSet();

  int count() const { return static_cast<int>(shards_.size()); }
  int split_zoom() const { return meta_.split_zoom; }
  tileformat::PackageKind kind() const { return kind_; }
  // Shard i (by its index, not by the order given).
  const std::string& path(int i) const { return shards_[i].path; }
  tileformat::PackageReader& reader(int i) { return *shards_[i].reader; }
  tileformat::ShardTableReader& table(int i) { return *shards_[i].table; }
  // Shard 0's metadata (the same as every shard's but for name, zooms, the
  // command line and the shard keys).
  const tileformat::MetadataMap& metadata() const { return shards_[0].reader->metadata(); }

  // The shard whose subtrees hold `id` (zoom >= split zoom), or that lists
  // it as a coarse tile (above the split zoom); -1 for none.
  int owner(tileformat::TileId id) const;
  // Every shard's tiles of zoom z (>= split zoom), sorted by (y, x).
  std::vector<tileformat::TileId> tiles(int z);
  // Copies every tile of zooms min_zoom..max_zoom into `writer`, zoom by
  // zoom in the one-machine order ((y, x) within a zoom), checkpointing after
  // each zoom: from their subtree's shard, or above the split zoom from the
  // shard that lists them as coarse tiles, else shard 0 (which built the
  // zooms above the split). Skips the tiles a resumed
  // writer holds. Throws InputError for a tile in two shards or outside its
  // shard's subtrees.
  void copy_tiles(tileformat::PackageWriter& writer, int min_zoom, int max_zoom,
                  Progress& progress);
  // The metadata of the merged package: the shards' keys as the whole build
  // writes them (its own name, `coarsest` zoom and center zoom, the merge's
  // command line), without the shard keys.
  tileformat::MetadataMap merged_metadata(const std::string& output, int coarsest,
                                          const std::string& command_line) const;

 private:
  struct Shard {
    std::string path;
    std::unique_ptr<tileformat::PackageReader> reader;
    std::unique_ptr<tileformat::ShardTableReader> table;
  };
  std::vector<Shard> shards_;  // by index
  tileformat::ShardMetadata meta_;
  tileformat::PackageKind kind_{};
  std::map<tileformat::TileId, int> roots_;  // subtree root -> shard
};

}  // namespace globe
