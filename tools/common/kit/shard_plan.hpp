// Sharded builds (docs/scale-out.md): `--shard I/N` builds only the subtrees
// below a split zoom that fall to shard I. Subtrees are ordered along the
// Morton curve (so a shard's subtrees are mostly neighbours and its border
// short) and cut into N runs of about equal estimated work. Every shard
// computes the same cut from the same inputs, so shards never talk to each
// other; `merge` joins them.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tileformat/shard_table.hpp"
#include "tileformat/tile_id.hpp"

namespace globe {

class CliArgs;
struct BuildOptions;

struct ShardSpec {
  int index = 0, count = 1;  // I/N, 0 <= I < N
};

// "I/N"; throws UsageError naming --shard.
ShardSpec parse_shard(const std::string& text);
// --shard I/N and --split-zoom Z, into o.shard and o.split_zoom.
void declare_shard_options(CliArgs& cli, BuildOptions& o);

// Work of one tile of the finest zoom (what the estimate counts: data tiles,
// input pixels or vertices).
struct TileWork {
  tileformat::TileId id;
  uint64_t work = 1;
};

struct ShardPlan {
  int split_zoom = 0;
  uint64_t roots_total = 0;  // subtrees with work (and coarse tiles), all shards
  // This shard's subtree roots (tiles of the split zoom) and coarse tiles
  // (above it, when the plan has them), sorted.
  std::vector<tileformat::TileId> roots;
  uint64_t work = 0, work_total = 0;  // this shard's estimate, and all shards'

  // Whether the tile lies in one of this shard's subtrees or is one of its
  // coarse tiles.
  bool contains(tileformat::TileId id) const;
};

// The subtrees of `tiles` (all of one zoom >= min_zoom) below the split zoom
// (given, or the coarsest zoom >= min_zoom with at least 16 subtrees per
// shard) and shard spec.index's run of them. `coarse`: tiles above the split
// zoom that are shared out too, with their work (line tiles, which do not
// depend on their children; the other builders' coarse zooms come from the
// split zoom's tiles); each is placed on the Morton curve just before the
// first subtree it covers. Throws UsageError for a split zoom finer than the
// tiles or coarser than min_zoom.
ShardPlan plan_shard(const std::vector<TileWork>& tiles, int min_zoom,
                     std::optional<int> split_zoom, ShardSpec spec,
                     const std::vector<TileWork>& coarse = {});

// "shard I/N: R of T subtrees below zoom Z, W of V units of estimated work"
// (the note a shard's build starts with).
std::string shard_summary(const ShardPlan& plan, ShardSpec spec);

// The shard keys of a shard's package: o.shard, the plan, shard_build_id(o),
// and the whole build's minzoom and center zoom.
tileformat::ShardMetadata shard_metadata(const BuildOptions& o, const ShardPlan& plan, int min_zoom,
                                         int center_zoom);

// What identifies a build across its shards: the reproducible command line
// without --shard and -o, and each input's size and modification time;
// hashed (16 hex digits).
std::string shard_build_id(const BuildOptions& o);

}  // namespace globe
