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

  // The shard whose subtrees hold `id` (zoom >= split zoom); -1 for none.
  int owner(tileformat::TileId id) const;
  // Every shard's tiles of zoom z (>= split zoom), sorted by (y, x).
  std::vector<tileformat::TileId> tiles(int z);
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
