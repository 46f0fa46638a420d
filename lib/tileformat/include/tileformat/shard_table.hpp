// What a shard package holds beyond an ordinary package (docs/tileformat.md
// §10): its shard metadata keys, and the shard table of per-tile parts the
// merge needs (the subtree roots the shard built; builder-specific data such
// as node errors along the shard's border). The one place that knows the
// table's SQL.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tileformat/metadata.hpp"
#include "tileformat/package.hpp"

namespace tileformat {

struct ShardMetadata {
  int index = 0, count = 1;  // globe:shard "INDEX/COUNT"
  int split_zoom = 0;        // globe:shard_split_zoom
  uint64_t roots = 0;        // globe:shard_roots: subtrees of the whole build (every shard)
  std::string build;         // globe:shard_build: what identifies the build (hex)
  // The whole build's minzoom and center zoom (the shard's own keys describe
  // the shard): globe:shard_min_zoom, globe:shard_center_zoom.
  int min_zoom = 0, center_zoom = 0;
};

MetadataMap to_metadata(const ShardMetadata& m);
// nullopt for a package that is not a shard; throws FormatError (§10) for
// bad shard keys.
std::optional<ShardMetadata> read_shard_metadata(const MetadataMap& meta);
// The keys of `meta` without the shard keys (what a merged package holds).
MetadataMap without_shard_keys(MetadataMap meta);

// A builder's name for one kind of part (0..255); kShardRoot is the tables'
// own: one empty row per subtree root the shard built.
using ShardPartTag = int;
inline constexpr ShardPartTag kShardRoot = 0;

class ShardTableWriter {
 public:
  // Creates the table in the writer's open transaction unless a resumed
  // build's file already holds it. Rows join the writer's transaction, so
  // they are committed with the tiles put before them (PackageWriter ends a
  // batch only when the next tile comes).
  explicit ShardTableWriter(PackageWriter& writer);
  ~ShardTableWriter();
  // Whether a resumed build's file already held the table (with every row
  // put before the table's first commit, such as the roots).
  bool continued() const { return continued_; }
  void put(ShardPartTag tag, TileId id, std::span<const uint8_t> data);
  // The shard's subtree roots (kShardRoot rows), put first in a build; a
  // continued table holds them already and is left as it is.
  void put_roots(const std::vector<TileId>& roots);

 private:
  std::unique_ptr<SqliteStatement> insert_;
  bool continued_ = false;
};

class ShardTableReader {
 public:
  // Throws FormatError if the package has no shard table.
  explicit ShardTableReader(PackageReader& reader);
  ~ShardTableReader();
  std::optional<std::vector<uint8_t>> get(ShardPartTag tag, TileId id);
  // Ids of one tag (every zoom), sorted.
  std::vector<TileId> list(ShardPartTag tag);

 private:
  PackageReader& reader_;
  std::unique_ptr<SqliteStatement> get_, list_;
};

}  // namespace tileformat
