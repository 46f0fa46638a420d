// Terrain package builder (see terrain_builder.hpp).
#include "terrain/terrain_builder.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>

#include "kit/package_output.hpp"
#include "kit/parallel_batches.hpp"
#include "kit/shard_plan.hpp"
#include "raster/data_probe.hpp"
#include "raster/raster_metadata.hpp"
#include "raster/raster_stages.hpp"
#include "raster/staged_package.hpp"
#include "raster/tile_groups.hpp"
#include "runtime/block_fill.hpp"
#include "runtime/error_tree.hpp"
#include "runtime/errors.hpp"
#include "terrain/terrain_stages.hpp"
#include "terrain/tile_warper.hpp"
#include "tileformat/blob_header.hpp"
#include "tileformat/error.hpp"
#include "tileformat/kpatch.hpp"
#include "tileformat/mblock.hpp"
#include "tileformat/metadata.hpp"
#include "tileformat/package.hpp"
#include "tileformat/shard_table.hpp"

namespace globe {
namespace {

using tileformat::KPatchLayout;
using tileformat::MBlock;
using tileformat::TileId;

constexpr int kFinalZstdLevel = 9;

// The passes of one zoom level, in order (StageCheckpoint::pass). Items are
// warp groups (finest zoom) or tiles; kPassEncode's progress is the tiles in
// the package itself.
enum Pass : int { kPassRaw = 0, kPassFinal = 1, kPassEncode = 2 };

// A shard's staged first rows and columns of the tiles just outside its
// subtrees (east, south, south-east of them) at the finest zoom.
constexpr tileformat::StageTag kHaloEdges = 16;

class Builder {
 public:
  Builder(const DemPlan& plan, const TerrainSettings& s, Progress& progress,
          const ShardPlan* shard = nullptr)
      : plan_(plan),
        s_(s),
        progress_(progress),
        size_(plan.steps + 1),
        layouts_{KPatchLayout(plan.steps, s.lattice, 0), KPatchLayout(plan.steps, s.lattice, 1)},
        threads_(s.worker_threads()),
        global_(plan.tiling.scheme != tileformat::Scheme::kLocal),
        shard_(shard) {}

  BuildSummary run() {
    const auto start = std::chrono::steady_clock::now();
    std::unique_ptr<tileformat::PackageWriter> writer =
        write_staged_package(s_, progress_, [&](tileformat::PackageWriter& w, StagingStore& stage) {
          with_shard_table(w, shard_, [&](tileformat::ShardTableWriter* parts) {
            parts_ = parts;
            levels(w, stage, plan_.max_zoom, shard_ ? shard_->split_zoom : plan_.min_zoom);
            parts_ = nullptr;
          });
        });
    if (writer->tiles_written() == 0 && !shard_)  // a shard may hold no data
      throw InputError(plan_.sources[0].path + ": no tile holds valid data in the requested area" +
                       (s_.bbox ? " (check --bbox)" : "") + "; nothing written");
    write_metadata(*writer);
    BuildSummary sum;
    commit_package(*writer, s_.output, start, sum);
    sum.samples = sum.tiles * static_cast<uint64_t>(size_) * size_;
    return sum;
  }

  // Zooms top down to bottom (inclusive); the stage holds what level top + 1
  // left (nothing at the finest zoom), or is a resumed build's.
  void levels(tileformat::PackageWriter& writer, StagingStore& stage, int top, int bottom) {
    // Where to start. Without the stage's checkpoint (none kept), every
    // level is computed again and only the package's committed tiles are
    // skipped.
    StageCheckpoint start{top, kPassRaw, 0};
    if (writer.resumed())
      if (const std::optional<StageCheckpoint> at = stage.checkpoint()) {
        start = *at;
        static const char* const kPassNames[] = {"samples", "errors", "encoding"};
        if (start.z < top || start.pass > kPassRaw || start.done > 0)
          progress_.note("continuing at zoom " + std::to_string(start.z) + ", " +
                         kPassNames[std::clamp(start.pass, 0, 2)] + " pass, after " +
                         std::to_string(start.done) + " items");
      }
    warpers_.resize(threads_);
    for (int z = top; z >= bottom; --z) {
      if (z > start.z) {  // finished before the interruption
        if (writer.tiles_at_zoom(z) > 0) coarsest_written_ = z;
        continue;
      }
      const StageCheckpoint from = z == start.z ? start : StageCheckpoint{z, kPassRaw, 0};
      if (from.pass <= kPassRaw) pass_raw(stage, z, from.pass == kPassRaw ? from.done : 0);
      if (from.pass <= kPassFinal) {
        pass_final(stage, z, from.pass == kPassFinal ? from.done : 0);
        stage.drop(Stage::kRaw, z);
        stage.drop(Stage::kEdges, z);
        stage.drop(Stage::kFinal, z + 1);
        stage.drop(Stage::kNodeErrors, z + 1);
        stage.drop(Stage::kQuarter, z + 1);
        stage.commit({z, kPassEncode, 0});
      }
      pass_encode(stage, writer, z);
      // The package holds level z before the stage forgets its inputs.
      writer.checkpoint();
      stage.commit({z - 1, kPassRaw, 0});
    }
    warpers_.clear();
  }

  int coarsest_written() const { return coarsest_written_; }

 private:
  // Whether this build computes the tile (zoom >= the split zoom for a shard).
  bool in_region(TileId id) const { return !shard_ || shard_->contains(id); }
  // A shard's tile just outside its subtrees whose first row or column a
  // tile inside takes (east, south or south-east of one).
  bool in_halo(TileId id) const {
    if (!shard_ || shard_->contains(id)) return false;
    for (auto [dx, dy] : {std::pair{-1, 0}, std::pair{0, -1}, std::pair{-1, -1}})
      if (auto nb = neighbour(id, dx, dy); nb && shard_->contains(*nb)) return true;
    return false;
  }
  // A shard's tile with a tile of another shard within `reach` tiles: its
  // vertex errors (reach 1) or its node errors (reach 2, read by those) are
  // completed by the merge.
  bool near_border(TileId id, int reach) const {
    for (int dy = -reach; dy <= reach; ++dy)
      for (int dx = -reach; dx <= reach; ++dx)
        if (auto nb = neighbour(id, dx, dy); nb && !shard_->contains(*nb)) return true;
    return false;
  }

  // Final blocks: the best height coding, encoded once here (pass 3 only
  // swaps in the error tree).
  std::vector<uint8_t> encode_final(const Block& b) const {
    MBlock m;
    m.size = size_;
    m.lattice = s_.lattice;
    m.step = plan_.step_m;
    m.q = b.q;
    if (std::any_of(b.valid.begin(), b.valid.end(), [](uint8_t v) { return v == 0; }))
      m.valid = b.valid;
    m.vertex_error.assign(layouts_[0].vertex_count(), 0);
    return tileformat::encode_mblock(m, kFinalZstdLevel, tileformat::HeightCoding::kBestPacking);
  }
  std::optional<TileId> neighbour(TileId id, int dx, int dy) const {
    const int64_t nx = static_cast<int64_t>(plan_.tiling.tiles_x(id.z)),
                  ny = static_cast<int64_t>(plan_.tiling.tiles_y(id.z));
    int64_t x = int64_t{id.x} + dx, y = int64_t{id.y} + dy;
    if (y < 0 || y >= ny) return std::nullopt;
    if (x < 0 || x >= nx) {
      if (!global_) return std::nullopt;
      x = (x + nx) % nx;
    }
    return TileId{id.z, static_cast<uint32_t>(x), static_cast<uint32_t>(y)};
  }

  struct FinalOut {
    std::vector<uint8_t> block, errors;  // both empty: the tile holds no data
    std::vector<uint8_t> quarter;        // for the parent; empty at the coarsest zoom
  };
  struct RawOut {
    std::vector<uint8_t> block, edges;  // both empty: no valid sample
    // The finest zoom: the tile finished in its warp group (`block` empty),
    // when the group holds the neighbours whose edges it takes.
    std::optional<FinalOut> final;
  };

  // Pass 1: raw samples of every tile of zoom z, from item `first` on.
  void pass_raw(StagingStore& stage, int z, size_t first) {
    if (z == plan_.max_zoom) return pass_warp(stage, z, first);
    std::vector<TileId> tiles;
    for (const TileId& c : stage.list(Stage::kFinal, z + 1))
      tiles.push_back(c.parent());
    sort_tiles(tiles);
    using Blobs = std::map<TileId, std::vector<uint8_t>>;
    progress_.begin("z" + std::to_string(z) + " pyramid", tiles.size());
    progress_.advance(first);
    parallel_batches<Blobs, RawOut>(
        tiles.size(), threads_, batch_size(),
        [&](size_t begin, size_t end) {
          Blobs children;
          for (size_t i = begin; i < end; ++i)
            for (const TileId& c : tiles[i].children())
              if (auto b = stage.get(Stage::kQuarter, c)) children.emplace(c, std::move(*b));
          return children;
        },
        [&](size_t i, int, const Blobs& children) { return decimate(tiles[i], children); },
        [&](size_t i, RawOut&& out) {
          store_raw(stage, tiles[i], out);
          progress_.advance();
        },
        [&](size_t done) {
          stage.commit_if_due({z, kPassRaw, done});
        },
        first);
    progress_.end();
  }

  // The finest zoom: tiles are warped in fixed groups of up to 4 x 4 (one
  // GDAL call each); groups depend only on tile positions, not on -j.
  void pass_warp(StagingStore& stage, int z, size_t first) {
    const std::vector<TileId> tiles = tiles_in_areas(plan_.tiling, plan_.data_areas, z);
    const int g = plan_.tiling.tiles_x(z) >= 16 ? TileWarper::kMaxGroup : 1;
    // The same groups as the whole build (a group's GDAL call decides its
    // samples); a shard warps those holding its tiles or its halo.
    std::vector<WarpGroup> groups = group_tiles(tiles, g);
    if (shard_)
      std::erase_if(groups, [&](const WarpGroup& group) {
        return std::none_of(group.members.begin(), group.members.end(),
                            [&](TileId id) { return in_region(id) || in_halo(id); });
      });
    size_t members = 0;
    for (const WarpGroup& group : groups)
      members += group.members.size();
    progress_.begin("z" + std::to_string(z) + " warp", members);
    for (size_t i = 0; i < first && i < groups.size(); ++i)
      progress_.advance(groups[i].members.size());
    parallel_batches<NoInputs, std::vector<RawOut>>(
        groups.size(), threads_, std::max<size_t>(1, batch_size() / 4),
        [](size_t, size_t) { return NoInputs{}; },
        [&](size_t i, int worker, const NoInputs&) {
          return warp_group(groups[i].first, groups[i].cols, groups[i].rows, groups[i].members,
                            worker);
        },
        [&](size_t i, std::vector<RawOut>&& outs) {
          for (size_t k = 0; k < outs.size(); ++k) {
            const TileId id = groups[i].members[k];
            if (in_region(id) && outs[k].final) {
              stage.put(Stage::kEdges, id, outs[k].edges);  // for the neighbouring groups
              store_final(stage, id, *outs[k].final);
            } else if (in_region(id))
              store_raw(stage, id, outs[k]);
            else if (in_halo(id) && !outs[k].edges.empty())
              stage.put(kHaloEdges, id, outs[k].edges);
            progress_.advance();
          }
        },
        [&](size_t done) {
          stage.commit_if_due({z, kPassRaw, done});
        },
        first);
    progress_.end();
  }

  static void store_raw(StagingStore& stage, TileId id, const RawOut& out) {
    if (out.block.empty()) return;
    stage.put(Stage::kRaw, id, out.block);
    stage.put(Stage::kEdges, id, out.edges);
  }
  static void store_final(StagingStore& stage, TileId id, const FinalOut& out) {
    if (out.block.empty()) return;
    stage.put(Stage::kFinal, id, out.block);
    stage.put(Stage::kNodeErrors, id, out.errors);
    if (!out.quarter.empty()) stage.put(Stage::kQuarter, id, out.quarter);
  }

  std::vector<RawOut> warp_group(TileId first, int cols, int rows,
                                 const std::vector<TileId>& members, int worker) {
    if (!warpers_[worker]) warpers_[worker] = std::make_unique<TileWarper>(plan_, s_.resampling);
    TileWarper::Window win;
    warpers_[worker]->warp(first, cols, rows, win);
    const int n = plan_.steps;
    const size_t stride = size_t(win.width);
    std::vector<std::optional<Block>> blocks;  // per member; none without valid samples
    for (const TileId& id : members) {
      // Samples a tile does not own (the last column and row, where a
      // neighbour exists) stay invalid here and come from it in pass 2.
      const OwnedSamples own = owned_samples(plan_.tiling, id, n);
      const size_t ox = size_t(id.x - first.x) * n, oy = size_t(id.y - first.y) * n;
      Block b{std::vector<int32_t>(size_t(size_) * size_, 0),
              std::vector<uint8_t>(size_t(size_) * size_, 0)};
      size_t valid = 0;
      for (int y = 0; y < own.rows; ++y)
        for (int x = 0; x < own.cols; ++x) {
          const double v = win.at((oy + y) * stride + ox + x);
          if (!std::isfinite(v)) continue;  // nodata, and infinite heights: holes
          const double qv = std::round(v / plan_.step_m);
          if (!(std::abs(qv) <= tileformat::kMaxQuantum))
            throw InputError(plan_.sources[0].path + ": height " + std::to_string(v) + " in tile " +
                             id.str() +
                             " does not fit the quantization grid; use a larger --precision");
          b.q[size_t(y) * size_ + x] = static_cast<int32_t>(qv);
          b.valid[size_t(y) * size_ + x] = 1;
          ++valid;
        }
      blocks.push_back(valid == 0 ? std::nullopt : std::optional<Block>(std::move(b)));
    }
    win = {};  // the blocks hold what is needed
    // Pass 2 here for each tile whose east, south and south-east neighbours
    // (where they exist) are members: their first rows and columns are in
    // `blocks`, so its raw block need not be staged. The rest wait for the
    // neighbouring groups.
    auto member = [&](TileId t) {
      const auto it = std::find(members.begin(), members.end(), t);
      return it == members.end() ? -1 : static_cast<int>(it - members.begin());
    };
    std::vector<RawOut> outs(members.size());
    for (size_t k = 0; k < members.size(); ++k) {
      if (!blocks[k]) continue;
      outs[k].edges = pack_edges(*blocks[k], size_);
    }
    for (size_t k = 0; k < members.size(); ++k) {
      if (!blocks[k]) continue;
      const TileId id = members[k];
      std::map<TileId, Block> edges;
      bool inside = in_region(id);
      for (auto [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}, std::pair{1, 1}})
        if (auto nb = neighbour(id, dx, dy)) {
          const int m = member(*nb);
          inside = inside && m >= 0 && in_region(*nb);
          if (inside && !outs[m].edges.empty())  // empty: no valid sample there
            edges.emplace(*nb, unpack_edges(outs[m].edges, size_));
        }
      if (inside)
        outs[k].final = finalize(id, std::move(*blocks[k]), edges, {});
      else
        outs[k].block = encode_scratch(*blocks[k], size_);
      blocks[k].reset();
    }
    return outs;
  }

  RawOut decimate(TileId id, const std::map<TileId, std::vector<uint8_t>>& cache) const {
    std::array<std::optional<Block>, 4> kids;  // every other sample of each child
    const auto children = id.children();
    for (int c = 0; c < 4; ++c)
      if (auto it = cache.find(children[c]); it != cache.end())
        kids[c] = decode_scratch(it->second);
    const int n = plan_.steps, h = n / 2, half = h + 1;
    Block b{std::vector<int32_t>(size_t(size_) * size_, 0),
            std::vector<uint8_t>(size_t(size_) * size_, 0)};
    size_t valid = 0;
    for (int y = 0; y <= n; ++y)
      for (int x = 0; x <= n; ++x) {
        // Children holding the sample (several on the middle lines): the
        // first one present gives it.
        for (int cy : {0, 1}) {
          if ((cy == 0 && y > h) || (cy == 1 && y < h)) continue;
          bool done = false;
          for (int cx : {0, 1}) {
            if ((cx == 0 && x > h) || (cx == 1 && x < h)) continue;
            const auto& k = kids[cx + 2 * cy];
            if (!k) continue;
            const size_t src = size_t(y - cy * h) * half + (x - cx * h),
                         dst = size_t(y) * size_ + x;
            if (k->valid[src]) {
              b.q[dst] = k->q[src];
              b.valid[dst] = 1;
              ++valid;
            }
            done = true;
            break;
          }
          if (done) break;
        }
      }
    if (valid == 0) return {};
    return RawOut{encode_scratch(b, size_), pack_edges(b, size_), std::nullopt};
  }

  // Pass 2: shared edges from the owners, hole filling, node errors.
  void pass_final(StagingStore& stage, int z, size_t first) {
    const std::vector<TileId> tiles = stage.list(Stage::kRaw, z);
    struct Inputs {
      std::map<TileId, std::vector<uint8_t>> raw, child_err;
      std::map<TileId, Block> edges;
    };
    progress_.begin("z" + std::to_string(z) + " errors", tiles.size());
    progress_.advance(first);
    parallel_batches<Inputs, FinalOut>(
        tiles.size(), threads_, batch_size(),
        [&](size_t begin, size_t end) {
          Inputs in;
          for (size_t i = begin; i < end; ++i) {
            if (auto b = stage.get(Stage::kRaw, tiles[i])) in.raw.emplace(tiles[i], std::move(*b));
            for (auto [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}, std::pair{1, 1}})
              if (auto nb = neighbour(tiles[i], dx, dy); nb && !in.edges.count(*nb)) {
                if (!in_region(*nb))
                  in.edges.emplace(*nb, halo_edges(stage, *nb));
                else if (auto e = stage.get(Stage::kEdges, *nb))
                  in.edges.emplace(*nb, unpack_edges(*e, size_));
              }
            if (z < plan_.max_zoom)
              for (const TileId& c : tiles[i].children())
                if (auto e = stage.get(Stage::kNodeErrors, c))
                  in.child_err.emplace(c, std::move(*e));
          }
          return in;
        },
        [&](size_t i, int, const Inputs& in) {
          return finalize(tiles[i], decode_scratch(in.raw.at(tiles[i])), in.edges, in.child_err);
        },
        [&](size_t i, FinalOut&& out) {
          store_final(stage, tiles[i], out);
          progress_.advance();
        },
        [&](size_t done) {
          stage.commit_if_due({z, kPassFinal, done});
        },
        first);
    progress_.end();
  }

  // The first row and column of a tile outside the shard, as the whole
  // build's pass 1 gives them: every sample there is the finest zoom's
  // sample at the same place (coarse samples equal fine ones), taken from
  // the staged halo edges of the finest tile that owns it (invalid where
  // that tile has no data).
  Block halo_edges(StagingStore& stage, TileId id) const {
    const int n = plan_.steps, zmax = plan_.max_zoom;
    const int up = zmax - id.z;
    const uint64_t cols = plan_.tiling.tiles_x(zmax), rows = plan_.tiling.tiles_y(zmax);
    std::map<TileId, std::optional<Block>> finest;
    Block e{std::vector<int32_t>(2 * size_t(size_), 0), std::vector<uint8_t>(2 * size_t(size_), 0)};
    for (size_t k = 0; k < 2 * size_t(size_); ++k) {
      const bool row = k < size_t(size_);
      const uint64_t sx = uint64_t{id.x} * n + (row ? k : 0),
                     sy = uint64_t{id.y} * n + (row ? 0 : k - size_);
      uint64_t gx = sx << up, gy = sy << up;
      uint64_t fx = gx / n, fy = gy / n, lx = gx % n, ly = gy % n;
      if (fx >= cols) {  // the east edge of the tiling: wraps, or the last tile owns it
        if (global_) {
          gx -= cols * n;
          fx = gx / n;
        } else {
          fx = cols - 1;
          lx = n;
        }
      }
      if (fy >= rows) {
        fy = rows - 1;
        ly = n;
      }
      const TileId f{zmax, static_cast<uint32_t>(fx), static_cast<uint32_t>(fy)};
      auto it = finest.find(f);
      if (it == finest.end()) {
        std::optional<Block> b;
        if (auto bytes = stage.get(kHaloEdges, f)) b = unpack_edges(*bytes, size_);
        it = finest.emplace(f, std::move(b)).first;
      }
      if (!it->second) continue;
      // Samples on a tile's first row or column: the places pass 2 reads.
      const size_t src = ly == 0 ? size_t(lx) : lx == 0 ? size_t(size_) + ly : SIZE_MAX;
      if (src == SIZE_MAX) continue;
      e.q[k] = it->second->q[src];
      e.valid[k] = it->second->valid[src];
    }
    return e;
  }

  FinalOut finalize(TileId id, Block b, const std::map<TileId, Block>& edges,
                    const std::map<TileId, std::vector<uint8_t>>& child_err) const {
    const int n = plan_.steps;
    // The last column and row belong to the east / south neighbours (first
    // column / row there), the far corner to the first of the south-east,
    // east and south neighbours that exists; at the tiling's edges, where
    // none exists, the block owns them.
    auto take = [&](int dx, int dy, size_t k, int x, int y) {
      auto nb = neighbour(id, dx, dy);
      if (!nb) return false;
      const size_t dst = size_t(y) * size_ + x;
      b.q[dst] = 0;
      b.valid[dst] = 0;
      if (auto it = edges.find(*nb); it != edges.end()) {
        b.q[dst] = it->second.q[k];
        b.valid[dst] = it->second.valid[k];
      }
      return true;
    };
    for (int y = 0; y < n; ++y)
      take(1, 0, size_t(size_) + y, n, y);
    for (int x = 0; x < n; ++x)
      take(0, 1, size_t(x), x, n);
    take(1, 1, 0, n, n) || take(1, 0, size_t(size_) + n, n, n) || take(0, 1, size_t(n), n, n);
    if (std::none_of(b.valid.begin(), b.valid.end(), [](uint8_t v) { return v != 0; })) return {};
    fill_holes(b.q, b.valid, size_, plan_.fill_q);

    std::array<std::vector<uint32_t>, 4> kids;
    std::array<const std::vector<uint32_t>*, 4> kid_ptrs{};
    const auto children = id.children();
    for (int c = 0; c < 4; ++c)
      if (auto it = child_err.find(children[c]); it != child_err.end()) {
        kids[c] = unpack_errors(it->second);
        kid_ptrs[c] = &kids[c];
      }
    const auto errors = node_errors(layouts_[id.diagonal()], b.q, b.valid, kid_ptrs);
    return FinalOut{
        encode_final(b), pack_errors(errors),
        id.z > plan_.min_zoom ? encode_quarter(b, plan_.steps) : std::vector<uint8_t>{}};
  }

  // Pass 3: vertex errors and the final MBlock. Tiles are put in list order,
  // so those a resumed package already holds are the first ones.
  void pass_encode(StagingStore& stage, tileformat::PackageWriter& writer, int z) {
    const std::vector<TileId> tiles = stage.list(Stage::kFinal, z);
    struct Inputs {
      std::map<TileId, std::vector<uint8_t>> finals;
      std::map<TileId, std::vector<uint32_t>> errs;
    };
    const size_t first = writer.resumed() ? writer.tiles_at_zoom(z) : 0;
    if (first > 0) coarsest_written_ = z;
    progress_.begin("z" + std::to_string(z) + " encode", tiles.size());
    progress_.advance(first);
    parallel_batches<Inputs, std::vector<uint8_t>>(
        tiles.size(), threads_, batch_size(),
        [&](size_t begin, size_t end) {
          Inputs in;
          for (size_t i = begin; i < end; ++i) {
            if (auto b = stage.get(Stage::kFinal, tiles[i]))
              in.finals.emplace(tiles[i], std::move(*b));
            for (int dy = -1; dy <= 1; ++dy)
              for (int dx = -1; dx <= 1; ++dx)
                if (auto nb = neighbour(tiles[i], dx, dy); nb && !in.errs.count(*nb))
                  if (auto e = stage.get(Stage::kNodeErrors, *nb))
                    in.errs.emplace(*nb, unpack_errors(*e));
          }
          return in;
        },
        [&](size_t i, int, const Inputs& in) {
          const TileId id = tiles[i];
          Neighbourhood nb{};
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
              if (auto t = neighbour(id, dx, dy))
                if (auto it = in.errs.find(*t); it != in.errs.end())
                  nb[dy + 1][dx + 1] = &it->second;
          return tileformat::replace_vertex_errors(
              in.finals.at(id), vertex_errors(layouts_[id.diagonal()], nb), kFinalZstdLevel);
        },
        [&](size_t i, std::vector<uint8_t>&& blob) {
          writer.put_tile(tiles[i], blob);
          if (parts_) put_shard_parts(stage, tiles[i]);
          coarsest_written_ = z;
          progress_.advance();
        },
        [](size_t) {}, first);
    progress_.end();
  }

  // What the merge needs of a shard's tile besides the tile: node errors
  // near the shard's border (the merge recomputes the vertex errors there)
  // and at the split zoom (with the quarter: the input of the zooms above).
  void put_shard_parts(StagingStore& stage, TileId id) {
    const bool split = id.z == shard_->split_zoom;
    if (split || near_border(id, 2))
      if (auto e = stage.get(Stage::kNodeErrors, id)) parts_->put(kShardNodeErrors, id, *e);
    if (split)
      if (auto q = stage.get(Stage::kQuarter, id)) parts_->put(kShardQuarter, id, *q);
  }

  void write_metadata(tileformat::PackageWriter& w) const {
    std::vector<tileformat::InputFile> inputs;
    for (const auto& src : plan_.sources)
      inputs.push_back({src.path, src.file_bytes});
    tileformat::TerrainMetadata m;
    m.common =
        raster_common_metadata({s_.output, tileformat::kMBlockFormat, "Terrain (MBlock/KPatch)",
                                s_.command_line, coarsest_written_, plan_.max_zoom},
                               std::move(inputs), plan_);
    m.resampling = s_.resampling;
    m.block_size = size_;
    m.lattice = s_.lattice;
    m.height_step = plan_.step_m;
    m.fill_height = plan_.fill_q * plan_.step_m;
    w.set_metadata(tileformat::to_metadata(m));
    // Terrain has tiles down to the coarsest zoom wherever it has data.
    if (shard_)
      w.set_metadata(tileformat::to_metadata(shard_metadata(
          s_, *shard_, plan_.min_zoom, raster_center_zoom(plan_, plan_.min_zoom, plan_.max_zoom))));
  }

  size_t batch_size() const { return static_cast<size_t>(8 * threads_); }

  const DemPlan& plan_;
  const TerrainSettings& s_;
  Progress& progress_;
  const int size_;
  const std::array<KPatchLayout, 2> layouts_;
  const int threads_;
  const bool global_;
  const ShardPlan* shard_;
  tileformat::ShardTableWriter* parts_ = nullptr;  // a shard's, while its levels are built
  std::vector<std::unique_ptr<TileWarper>> warpers_;
  int coarsest_written_ = 0;
};

}  // namespace

BuildSummary build_terrain(const DemPlan& plan, const TerrainSettings& settings,
                           Progress& progress) {
  if (!settings.shard) return Builder(plan, settings, progress).run();
  // Work per subtree: its finest tiles, weighted by how much valid data
  // they hold.
  std::vector<ProbeBand> bands;
  for (const DemSource& src : plan.sources)
    bands.push_back({1, false, src.nodata});
  const ShardPlan shard = plan_raster_shard(plan, {plan.sources.begin(), plan.sources.end()}, bands,
                                            settings, progress);
  return Builder(plan, settings, progress, &shard).run();
}

int build_terrain_levels(const DemPlan& plan, const TerrainSettings& settings,
                         tileformat::PackageWriter& writer, StagingStore& stage, int top,
                         Progress& progress) {
  Builder b(plan, settings, progress);
  b.levels(writer, stage, top, plan.min_zoom);
  return b.coarsest_written();
}

}  // namespace globe
