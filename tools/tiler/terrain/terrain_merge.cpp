// Terrain shard merge (see terrain_merge.hpp).
#include "terrain/terrain_merge.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>

#include "kit/package_output.hpp"
#include "kit/parallel_batches.hpp"
#include "raster/staged_package.hpp"
#include "runtime/error_tree.hpp"
#include "runtime/package_open.hpp"
#include "terrain/terrain_stages.hpp"
#include "tileformat/error.hpp"
#include "tileformat/kpatch.hpp"
#include "tileformat/mblock.hpp"
#include "tileformat/metadata.hpp"

namespace globe {
namespace {

using tileformat::TileId;

constexpr int kFinalZstdLevel = 9;  // as the builder's final blocks

class Merger {
 public:
  Merger(ShardSet& shards, const BuildOptions& o, Progress& progress)
      : shards_(shards), o_(o), progress_(progress) {
    const std::string& first = shards.path(0);
    meta_ =
        read_metadata(first, [&] { return tileformat::read_terrain_metadata(shards.metadata()); });
    shard_ = *tileformat::read_shard_metadata(shards.metadata());
    tiling_ = meta_.common.tiling;
    if (meta_.block_size < 3 || meta_.lattice < 1 || !(meta_.height_step > 0))
      throw InputError(first + ": bad terrain block facts in the metadata");
    steps_ = meta_.block_size - 1;
    for (int diagonal : {0, 1})
      layouts_.emplace_back(steps_, meta_.lattice, diagonal);
  }

  BuildSummary run() {
    const auto start = std::chrono::steady_clock::now();
    int coarsest = shards_.split_zoom();
    std::unique_ptr<tileformat::PackageWriter> writer =
        write_staged_package(o_, progress_, [&](tileformat::PackageWriter& w, StagingStore& stage) {
          const bool above_done = w.resumed() && stage.checkpoint().has_value();
          for (int z = meta_.common.max_zoom; z >= shards_.split_zoom(); --z)
            copy_zoom(w, z);
          if (shards_.split_zoom() > shard_.min_zoom) {
            if (!above_done) seed(stage);
            coarsest = build_terrain_levels(plan(), settings(), w, stage, shards_.split_zoom() - 1,
                                            progress_);
          }
        });
    if (writer->tiles_written() == 0)
      throw InputError("the shards hold no tiles; nothing written to " + o_.output);
    writer->set_metadata(shards_.merged_metadata(o_.output, coarsest, o_.command_line));
    BuildSummary sum;
    commit_package(*writer, o_.output, start, sum);
    sum.samples = sum.tiles * uint64_t(meta_.block_size) * uint64_t(meta_.block_size);
    return sum;
  }

 private:
  std::optional<TileId> neighbour(TileId id, int dx, int dy) const {
    const int64_t nx = static_cast<int64_t>(tiling_.tiles_x(id.z)),
                  ny = static_cast<int64_t>(tiling_.tiles_y(id.z));
    int64_t x = int64_t{id.x} + dx, y = int64_t{id.y} + dy;
    if (y < 0 || y >= ny) return std::nullopt;
    if (x < 0 || x >= nx) {
      if (!tiling_.wraps_x()) return std::nullopt;
      x = (x + nx) % nx;
    }
    return TileId{id.z, static_cast<uint32_t>(x), static_cast<uint32_t>(y)};
  }

  // A neighbour in another shard: the shard wrote this tile's vertex errors
  // without that neighbour's node errors.
  bool on_border(TileId id, int owner) const {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (auto nb = neighbour(id, dx, dy)) {
          const int o = shards_.owner(*nb);
          if (o >= 0 && o != owner) return true;
        }
    return false;
  }

  std::vector<uint32_t> node_errors(TileId id) {
    const int o = shards_.owner(id);
    if (o < 0) return {};
    auto bytes = shards_.table(o).get(kShardNodeErrors, id);
    if (!bytes) {
      if (!shards_.reader(o).has_tile(id)) return {};  // no data there
      throw InputError(shards_.path(o) + ": tile " + id.str() +
                       " has no node errors in the shard table; rebuild the shard");
    }
    return unpack_errors(*bytes);
  }

  struct Item {
    std::vector<uint8_t> blob;
    // Border tiles: the 3 x 3 neighbourhood's node errors (empty: no block).
    std::optional<std::array<std::array<std::vector<uint32_t>, 3>, 3>> errors;
  };

  // Level z (>= split zoom): every shard's tiles in (y, x) order, as the
  // whole build puts them; a resumed merge skips those already committed.
  void copy_zoom(tileformat::PackageWriter& writer, int z) {
    const std::vector<TileId> tiles = shards_.tiles(z);
    for (size_t i = 1; i < tiles.size(); ++i)
      if (tiles[i] == tiles[i - 1])
        throw InputError("tile " + tiles[i].str() + " is in two shards; the shards overlap");
    const size_t first = writer.resumed() ? writer.tiles_at_zoom(z) : 0;
    progress_.begin("z" + std::to_string(z) + " merge", tiles.size());
    progress_.advance(first);
    const int threads = o_.worker_threads();
    using Batch = std::map<TileId, Item>;
    parallel_batches<Batch, std::vector<uint8_t>>(
        tiles.size(), threads, size_t(64) * threads,
        [&](size_t begin, size_t end) {
          Batch batch;
          for (size_t i = begin; i < end; ++i) {
            const TileId id = tiles[i];
            const int owner = shards_.owner(id);
            if (owner < 0)
              throw InputError("tile " + id.str() +
                               " lies in no shard's subtrees; the shards do "
                               "not come from one build");
            Item item;
            auto blob = shards_.reader(owner).tile(id);
            if (!blob)
              throw InputError(shards_.path(owner) + ": tile " + id.str() +
                               " is listed but unreadable");
            item.blob = std::move(*blob);
            if (on_border(id, owner)) {
              item.errors.emplace();
              for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                  if (auto nb = neighbour(id, dx, dy))
                    (*item.errors)[dy + 1][dx + 1] = node_errors(*nb);
            }
            batch.emplace(id, std::move(item));
          }
          return batch;
        },
        [&](size_t i, int, const Batch& batch) {
          const TileId id = tiles[i];
          const Item& item = batch.at(id);
          if (!item.errors) return item.blob;
          Neighbourhood nb{};
          for (int dy = 0; dy < 3; ++dy)
            for (int dx = 0; dx < 3; ++dx)
              if (!(*item.errors)[dy][dx].empty()) nb[dy][dx] = &(*item.errors)[dy][dx];
          try {
            return tileformat::replace_vertex_errors(
                item.blob, vertex_errors(layouts_[id.diagonal()], nb), kFinalZstdLevel);
          } catch (const std::exception& e) {
            throw InputError(shards_.path(shards_.owner(id)) + ": tile " + id.str() + ": " +
                             e.what() + "; rebuild the shard");
          }
        },
        [&](size_t i, std::vector<uint8_t>&& blob) {
          writer.put_tile(tiles[i], blob);
          progress_.advance();
        },
        [](size_t) {}, first);
    progress_.end();
    writer.checkpoint();
  }

  // The split zoom as the builder leaves it for the next coarser level.
  void seed(StagingStore& stage) {
    const int s = shards_.split_zoom();
    for (const TileId& id : shards_.tiles(s)) {
      const int o = shards_.owner(id);
      auto errors = shards_.table(o).get(kShardNodeErrors, id);
      auto quarter = shards_.table(o).get(kShardQuarter, id);
      if (!errors || !quarter)
        throw InputError(shards_.path(o) + ": tile " + id.str() +
                         " (split zoom) lacks its node errors or quarter; rebuild the shard");
      stage.put(Stage::kFinal, id, {});
      stage.put(Stage::kNodeErrors, id, *errors);
      stage.put(Stage::kQuarter, id, *quarter);
    }
    stage.commit({s - 1, 0, 0});
  }

  DemPlan plan() const {
    DemPlan p;
    p.tiling = tiling_;
    p.min_zoom = shard_.min_zoom;
    p.max_zoom = meta_.common.max_zoom;
    p.steps = steps_;
    p.step_m = meta_.height_step;
    p.fill_q = static_cast<int32_t>(std::llround(meta_.fill_height / meta_.height_step));
    return p;
  }
  TerrainSettings settings() const {
    TerrainSettings s;
    static_cast<BuildOptions&>(s) = o_;
    s.block_size = meta_.block_size;
    s.lattice = meta_.lattice;
    return s;
  }

  ShardSet& shards_;
  const BuildOptions& o_;
  Progress& progress_;
  tileformat::TerrainMetadata meta_;
  tileformat::ShardMetadata shard_;
  tileformat::Tiling tiling_;
  int steps_ = 0;
  std::vector<tileformat::KPatchLayout> layouts_;  // by diagonal
};

}  // namespace

BuildSummary merge_terrain(ShardSet& shards, const BuildOptions& o, Progress& progress) {
  return Merger(shards, o, progress).run();
}

}  // namespace globe
