// The out-of-core flow solver (see flow_solver.hpp).
#include "flow_solver.hpp"

#include <algorithm>

#include "batch_blocks.hpp"
#include "chunk_heights.hpp"
#include "depression_fill.hpp"
#include "flow_accumulation.hpp"
#include "flow_directions.hpp"
#include "parallel_batches.hpp"
#include "scratch_array_file.hpp"

namespace globe::flow {

namespace {

// Bytes a worker holds per chunk cell at the busiest pass (the directions:
// filled heights read back and windowed, distances and keys, the flat
// cells' queue, receivers, areas, Kahn's order and links).
constexpr uint64_t kBytesPerCell = 60;
// Bytes per perimeter cell at the busiest moment of the run (the perimeter
// graph's solve; the watershed graph's edges are deduplicated per chunk).
constexpr uint64_t kBytesPerNode = 64;

using tileformat::TileId;

struct Perimeters {            // per node (perimeter cell of a chunk), in slot order
  std::vector<uint64_t> base;  // per slot: its first node
  std::vector<int32_t> height, filled;
  std::vector<uint32_t> label;  // global watershed
  std::vector<uint32_t> distance;
  std::vector<int32_t> key;  // flats: the height the way off the flat leads to
  std::vector<uint8_t> flat, changed;
  int64_t node(int slot, int index) const { return int64_t(base[size_t(slot)]) + index; }
};

class Solver {
 public:
  Solver(const TerrainPackage& p, const FlowSettings& s, Progress& progress)
      : p_(p), s_(s), progress_(progress) {}

  FlowSolution run() {
    const std::vector<TileId> finest = p_.reader->tile_ids(p_.max_zoom);
    const int64_t c =
        chunk_size_for(p_.tiling, p_.max_zoom, p_.block_size, finest, s_.memory_bytes, s_.threads);
    out_.grid = std::make_unique<FlowGrid>(p_.tiling, p_.max_zoom, p_.block_size, finest, c);
    const FlowGrid& g = *out_.grid;
    const auto& chunks = g.chunks();
    per_.base.assign(chunks.size() + 1, 0);
    cell_base_.assign(chunks.size() + 1, 0);
    for (size_t k = 0; k < chunks.size(); ++k) {
      per_.base[k + 1] = per_.base[k] + uint64_t(chunks[k].perimeter_count());
      cell_base_[k + 1] = cell_base_[k] + chunks[k].cells();
    }
    const size_t nodes = per_.base.back();
    out_.perimeter_cells = nodes;
    // One chunk fits the budget with room for its scratch data (21 bytes a
    // cell against kBytesPerCell): then the scratch stays in memory.
    const uint64_t cells = cell_base_.back();
    const bool in_memory = chunks.size() == 1;
    auto memory = [&](uint64_t bytes) {
      return in_memory ? std::optional<uint64_t>(bytes) : std::nullopt;
    };
    fill_ = std::make_unique<ScratchArrayFile>(s_.scratch_prefix + "fill.bin", memory(cells * 8));
    fill_pass();
    route_flats();
    dirs_ = std::make_unique<ScratchArrayFile>(s_.scratch_prefix + "receivers.bin", memory(cells));
    out_.pyramid = std::make_unique<FlowPyramid>(g, p_.min_zoom, s_.scratch_prefix, in_memory);
    accumulate();
    dirs_.reset();
    out_.pyramid->finish();
    return std::move(out_);
  }

 private:
  const FlowGrid& grid() const { return *out_.grid; }
  const Chunk& chunk(int slot) const { return grid().chunks()[size_t(slot)]; }

  // Runs `compute(slot)` for the slots in parallel, then `consume` in order.
  template <typename Result>
  void each_chunk(const std::string& phase, const std::vector<int>& slots,
                  const std::function<Result(int slot, const BatchBlocks& blocks)>& compute,
                  const std::function<void(int slot, Result&&)>& consume, bool read_blocks) {
    progress_.begin(phase, slots.size());
    parallel_batches<BatchBlocks, Result>(
        slots.size(), s_.threads, 1,
        [&](size_t begin, size_t end) {
          BatchBlocks blocks;
          if (read_blocks)
            for (size_t i = begin; i < end; ++i)
              for (const TileId& t : chunk_tiles(grid(), chunk(slots[i])))
                blocks.add(t, p_.reader->tile(t));
          return blocks;
        },
        [&](size_t i, int, const BatchBlocks& blocks) { return compute(slots[i], blocks); },
        [&](size_t i, Result&& r) {
          consume(slots[i], std::move(r));
          progress_.advance();
        },
        [](size_t) {});
    progress_.end();
  }

  std::vector<int> all_slots() const {
    std::vector<int> v(grid().chunks().size());
    for (size_t i = 0; i < v.size(); ++i)
      v[i] = int(i);
    return v;
  }

  // The node of the perimeter cell at global (x, y), or -1 (off the grid, no chunk).
  int64_t node_at(int64_t x, int64_t y) const {
    if (!grid().normalise(x, y)) return -1;
    const int slot = grid().slot_of(x, y);
    if (slot < 0) return -1;
    const Chunk& c = chunk(slot);
    const int i = c.perimeter_index(int(x - c.x0), int(y - c.y0));
    return i < 0 ? -1 : per_.node(slot, i);
  }

  // Calls fn(m) for the node m of each cell of another chunk (or of this one,
  // across the wrap) that touches perimeter cell i of the chunk.
  template <typename F>
  void outer_neighbours(int slot, int i, F fn) const {
    const Chunk& c = chunk(slot);
    int x, y;
    c.perimeter_cell(i, x, y);
    for (int d = 1; d <= 8; ++d) {
      const int nx = x + kDx[d], ny = y + kDy[d];
      if (nx >= 0 && ny >= 0 && nx < c.w && ny < c.h) continue;
      const int64_t m = node_at(c.x0 + nx, c.y0 + ny);
      if (m >= 0) fn(m);
    }
  }

  // The nodes of the window ring of a chunk (-1 where none), in ring order:
  // north row, south row, west column, east column (corners in the rows).
  std::vector<int64_t> ring_nodes(const Chunk& c) const {
    std::vector<int64_t> r;
    for (int y : {-1, c.h})
      for (int x = -1; x <= c.w; ++x)
        r.push_back(node_at(c.x0 + x, c.y0 + y));
    for (int x : {-1, c.w})
      for (int y = 0; y < c.h; ++y)
        r.push_back(node_at(c.x0 + x, c.y0 + y));
    return r;
  }
  template <typename T, typename F>
  void put_ring(const Chunk& c, std::vector<T>& window, const std::vector<int64_t>& ring,
                F value) const {
    const ChunkWindow win(c);
    size_t k = 0;
    for (int y : {-1, c.h})
      for (int x = -1; x <= c.w; ++x, ++k)
        window[win.at(x, y)] = value(ring[k]);
    for (int x : {-1, c.w})
      for (int y = 0; y < c.h; ++y, ++k)
        window[win.at(x, y)] = value(ring[k]);
  }

  // ---- 1, 2: depression filling ----
  struct FillResult {
    std::vector<int32_t> height;
    std::vector<uint32_t> label;  // local
    uint32_t labels = 0;
    std::vector<SpillEdge> edges;
  };

  void fill_pass() {
    const FlowGrid& g = grid();
    const size_t nodes = per_.base.back();
    per_.height.assign(nodes, kNoData);
    std::vector<uint32_t> local_label(nodes, 0);
    std::vector<uint32_t> labels(g.chunks().size(), 0);
    std::vector<std::vector<SpillEdge>> edges(g.chunks().size());
    each_chunk<FillResult>(
        "flow: fill depressions", all_slots(),
        [&](int slot, const BatchBlocks& blocks) {
          const Chunk& c = chunk(slot);
          const std::vector<int32_t> z =
              chunk_heights(g, c, [&](TileId t) { return blocks.get(t, s_.input); });
          ChunkFill f = fill_chunk(c, z);
          const uint64_t at = cell_base_[size_t(slot)] * 8;
          fill_->write_array<int32_t>(at, f.filled);
          fill_->write_array<uint32_t>(at + c.cells() * 4, f.label);
          FillResult r;
          for (int i = 0; i < c.perimeter_count(); ++i) {
            int x, y;
            c.perimeter_cell(i, x, y);
            r.height.push_back(z[ChunkWindow(c).at(x, y)]);
            r.label.push_back(f.label[size_t(y) * c.w + x]);
          }
          r.labels = f.labels;
          r.edges = std::move(f.edges);
          return r;
        },
        [&](int slot, FillResult&& r) {
          std::copy(r.height.begin(), r.height.end(), per_.height.begin() + per_.node(slot, 0));
          std::copy(r.label.begin(), r.label.end(), local_label.begin() + per_.node(slot, 0));
          labels[size_t(slot)] = r.labels;
          edges[size_t(slot)] = std::move(r.edges);
        },
        true);
    // Global watershed ids: 0 the data's edge, then each chunk's in turn.
    label_base_.assign(g.chunks().size(), 0);
    uint64_t next = 1;
    for (size_t k = 0; k < labels.size(); ++k) {
      label_base_[k] = next;
      next += labels[k] - 2;
    }
    out_.watersheds = next;
    std::vector<SpillEdge> all;
    for (size_t k = 0; k < edges.size(); ++k) {
      for (const SpillEdge& e : edges[k])
        all.push_back({global_label(int(k), e.a), global_label(int(k), e.b), e.level});
      std::vector<SpillEdge>().swap(edges[k]);
    }
    per_.label.assign(nodes, 0);
    for (size_t k = 0; k < g.chunks().size(); ++k)
      for (int i = 0; i < chunk(int(k)).perimeter_count(); ++i) {
        const int64_t n = per_.node(int(k), i);
        per_.label[size_t(n)] = global_label(int(k), local_label[size_t(n)]);
      }
    std::vector<uint32_t>().swap(local_label);
    // Spills across chunk edges, between touching perimeter cells: the
    // lowest per pair of watersheds, gathered chunk by chunk (a chunk's
    // border cells mostly share a few watersheds).
    SpillPairs pairs;
    for (size_t k = 0; k < g.chunks().size(); ++k) {
      pairs.clear();
      for (int i = 0; i < chunk(int(k)).perimeter_count(); ++i) {
        const int64_t n = per_.node(int(k), i);
        if (per_.height[size_t(n)] == kNoData) continue;
        outer_neighbours(int(k), i, [&](int64_t m) {
          if (m <= n || per_.height[size_t(m)] == kNoData) return;  // each pair once
          const uint32_t a = per_.label[size_t(n)], b = per_.label[size_t(m)];
          if (a != b) pairs.note(a, b, std::max(per_.height[size_t(n)], per_.height[size_t(m)]));
        });
      }
      pairs.append_to(all);
    }
    spill_ = spill_levels(next, all);
    std::vector<SpillEdge>().swap(all);
    // Perimeter cells keep only their filled height and watershed.
    per_.filled = std::move(per_.height);
    for (size_t n = 0; n < nodes; ++n)
      if (per_.filled[n] != kNoData)
        per_.filled[n] = std::max(per_.filled[n], spill_[per_.label[n]]);
  }

  uint32_t global_label(int slot, uint32_t local) const {
    return local == kEdgeLabel ? 0 : uint32_t(label_base_[size_t(slot)] + local - 2);
  }

  // The chunk's window of filled heights.
  std::vector<int32_t> filled_window(int slot, const std::vector<int64_t>& ring) const {
    const Chunk& c = chunk(slot);
    const ChunkWindow win(c);
    std::vector<int32_t> local(c.cells());
    std::vector<uint32_t> label(c.cells());
    const uint64_t at = cell_base_[size_t(slot)] * 8;
    fill_->read_array<int32_t>(at, local);
    fill_->read_array<uint32_t>(at + c.cells() * 4, label);
    std::vector<int32_t> f(win.size(), kNoData);
    for (int y = 0; y < c.h; ++y)
      for (int x = 0; x < c.w; ++x) {
        const size_t i = size_t(y) * c.w + x;
        if (local[i] != kNoData)
          f[win.at(x, y)] = std::max(local[i], spill_[global_label(slot, label[i])]);
      }
    put_ring(c, f, ring, [&](int64_t n) { return n < 0 ? kNoData : per_.filled[size_t(n)]; });
    return f;
  }

  // The chunk's windows of flat distances and keys.
  void flat_windows(int slot, const std::vector<int64_t>& ring, const std::vector<int32_t>& f,
                    std::vector<uint32_t>& d, std::vector<int32_t>& key) const {
    const Chunk& c = chunk(slot);
    d.assign(ChunkWindow(c).size(), kFar);
    key.assign(d.size(), kNoKey);
    put_ring(c, d, ring, [&](int64_t n) { return n < 0 ? kFar : per_.distance[size_t(n)]; });
    put_ring(c, key, ring, [&](int64_t n) { return n < 0 ? kNoKey : per_.key[size_t(n)]; });
    flat_distances(c, f, d, key);
  }

  // ---- 3: flats, iterated until the distances at chunk edges settle ----
  struct FlatResult {
    std::vector<uint32_t> distance;
    std::vector<int32_t> key;
    std::vector<uint8_t> flat;
  };

  void route_flats() {
    const size_t nodes = per_.base.back();
    per_.distance.assign(nodes, kFar);
    per_.key.assign(nodes, kNoKey);
    per_.flat.assign(nodes, 0);
    per_.changed.assign(nodes, 0);
    // A single chunk that does not wrap has no ring to wait for: the
    // directions pass computes its distances once.
    std::vector<int> run = all_slots();
    if (run.size() == 1 && !grid().wraps()) return;
    while (!run.empty()) {
      ++out_.flat_rounds;
      std::vector<std::pair<int, FlatResult>> results;
      each_chunk<FlatResult>(
          "flow: flats (round " + std::to_string(out_.flat_rounds) + ")", run,
          [&](int slot, const BatchBlocks&) {
            const Chunk& c = chunk(slot);
            const ChunkWindow win(c);
            const std::vector<int64_t> ring = ring_nodes(c);
            const std::vector<int32_t> f = filled_window(slot, ring);
            std::vector<uint32_t> d;
            std::vector<int32_t> key;
            flat_windows(slot, ring, f, d, key);
            FlatResult r;
            for (int i = 0; i < c.perimeter_count(); ++i) {
              int x, y;
              c.perimeter_cell(i, x, y);
              r.distance.push_back(d[win.at(x, y)]);
              r.key.push_back(key[win.at(x, y)]);
              // (flat_distances leaves 0 off a flat, kFar where no data)
              r.flat.push_back(f[win.at(x, y)] != kNoData && d[win.at(x, y)] != 0);
            }
            return r;
          },
          [&](int slot, FlatResult&& r) { results.emplace_back(slot, std::move(r)); }, false);
      // Applied after the round, so every chunk of a round saw the same ring.
      std::fill(per_.changed.begin(), per_.changed.end(), 0);
      for (auto& [slot, r] : results)
        for (size_t i = 0; i < r.distance.size(); ++i) {
          const size_t n = size_t(per_.node(slot, int(i)));
          per_.flat[n] = r.flat[i];
          if (per_.distance[n] != r.distance[i] || per_.key[n] != r.key[i]) {
            per_.distance[n] = r.distance[i];
            per_.key[n] = r.key[i];
            per_.changed[n] = 1;
          }
        }
      run.clear();
      for (int slot : all_slots())
        if (ring_changed_on_flat(slot)) run.push_back(slot);
    }
  }

  // Whether a flat perimeter cell of the chunk touches a cell of another
  // chunk at its height whose distance changed in the last round.
  bool ring_changed_on_flat(int slot) const {
    bool changed = false;
    for (int i = 0; i < chunk(slot).perimeter_count() && !changed; ++i) {
      const int64_t n = per_.node(slot, i);
      if (!per_.flat[size_t(n)]) continue;
      outer_neighbours(slot, i, [&](int64_t m) {
        changed |= per_.changed[size_t(m)] && per_.filled[size_t(m)] == per_.filled[size_t(n)];
      });
    }
    return changed;
  }

  // ---- 4, 5, 6: receivers, accumulation ----
  struct LinkResult {
    PerimeterFlow flow;
    std::vector<int64_t> target;  // per perimeter cell: the node it drains into, or -1
  };

  void accumulate() {
    const size_t nodes = per_.base.back();
    std::vector<uint64_t> area(nodes, 0);
    std::vector<int64_t> successor(nodes, kNoNode);
    std::vector<uint8_t> crosses(nodes, 0);
    // A single chunk that does not wrap receives nothing from outside: its
    // own accumulation is final and goes straight to the pyramid.
    const bool alone = grid().chunks().size() == 1 && !grid().wraps();
    each_chunk<LinkResult>(
        "flow: directions", all_slots(),
        [&](int slot, const BatchBlocks&) {
          const Chunk& c = chunk(slot);
          const std::vector<int64_t> ring = ring_nodes(c);
          const std::vector<int32_t> f = filled_window(slot, ring);
          std::vector<uint32_t> d;
          std::vector<int32_t> key;
          flat_windows(slot, ring, f, d, key);
          const std::vector<uint8_t> rec = d8_receivers(grid(), c, f, d, key);
          LinkResult r;
          std::vector<uint64_t> acc = accumulate_chunk(grid(), c, rec, {}, &r.flow);
          if (alone) {
            LevelGrid level;
            level.x0 = c.x0, level.y0 = c.y0, level.w = c.w, level.h = c.h;
            level.area = std::move(acc);
            level.code = rec;
            out_.pyramid->put_chunk(slot, std::move(level));
          } else {
            dirs_->write_array<uint8_t>(cell_base_[size_t(slot)], rec);
          }
          r.target.assign(r.flow.leaves.size(), kNoNode);
          for (size_t i = 0; i < r.flow.leaves.size(); ++i) {
            if (!r.flow.leaves[i]) continue;
            int x, y;
            c.perimeter_cell(int(i), x, y);
            const uint8_t code = rec[size_t(y) * c.w + x];
            r.target[i] = node_at(c.x0 + x + kDx[code], c.y0 + y + kDy[code]);
          }
          return r;
        },
        [&](int slot, LinkResult&& r) {
          for (size_t i = 0; i < r.target.size(); ++i) {
            const size_t n = size_t(per_.node(slot, int(i)));
            area[n] = r.flow.area[i];
            if (r.flow.leaves[i]) {
              successor[n] = r.target[i];
              crosses[n] = 1;
            } else if (r.flow.next[i] >= 0) {
              successor[n] = per_.node(slot, r.flow.next[i]);
            }
          }
        },
        false);
    fill_.reset();  // the filled heights are no longer needed, nor the perimeters' state
    Perimeters kept;
    kept.base = std::move(per_.base);
    per_ = std::move(kept);
    std::vector<int32_t>().swap(spill_);
    if (alone) return;
    const std::vector<uint64_t> inflow = solve_inflows(area, successor, crosses);
    each_chunk<int>(
        "flow: accumulate", all_slots(),
        [&](int slot, const BatchBlocks&) {
          const Chunk& c = chunk(slot);
          std::vector<uint8_t> rec(c.cells());
          dirs_->read_array<uint8_t>(cell_base_[size_t(slot)], rec);
          const auto first = inflow.begin() + per_.node(slot, 0);
          const std::vector<uint64_t> in(first, first + c.perimeter_count());
          LevelGrid level;
          level.x0 = c.x0, level.y0 = c.y0, level.w = c.w, level.h = c.h;
          level.area = accumulate_chunk(grid(), c, rec, in, nullptr);
          level.code = std::move(rec);
          out_.pyramid->put_chunk(slot, std::move(level));
          return 0;
        },
        [](int, int&&) {}, false);
  }

  const TerrainPackage& p_;
  const FlowSettings& s_;
  Progress& progress_;
  FlowSolution out_;
  Perimeters per_;
  std::vector<uint64_t> cell_base_;   // per slot: its first cell in the scratch files
  std::vector<uint64_t> label_base_;  // per slot: global id of its local label 2
  std::vector<int32_t> spill_;        // per global watershed
  std::unique_ptr<ScratchArrayFile> fill_, dirs_;
};

}  // namespace

int64_t chunk_size_for(const tileformat::Tiling& t, int zoom, int block_size,
                       const std::vector<TileId>& finest, uint64_t memory_bytes, int threads) {
  const int64_t steps = block_size - 1;
  const int64_t cols = int64_t(t.tiles_x(zoom)) * steps, rows = int64_t(t.tiles_y(zoom)) * steps;
  const int64_t whole = std::max(cols, rows);
  // Workers' chunks grow with C, the perimeters kept for the whole run
  // shrink: the largest C that fits, else the cheapest.
  int64_t best = 0, cheapest = 64;
  uint64_t cheapest_bytes = UINT64_MAX, best_cells = UINT64_MAX;
  for (int64_t c = 64; c < 2 * whole; c *= 2) {
    const uint64_t side = uint64_t(std::min(c, whole) + 2);
    const uint64_t tiles = uint64_t(c / steps + 3) * uint64_t(c / steps + 3);
    const uint64_t worker = side * side * kBytesPerCell + tiles * block_size * block_size * 5;
    int64_t cx = 0, cy = 0;
    const std::vector<uint8_t> present =
        FlowGrid::present_chunks(t, zoom, int(steps), finest, c, cx, cy);
    const uint64_t chunks =
        std::max<uint64_t>(1, uint64_t(std::count(present.begin(), present.end(), 1)));
    // Cost: the chunks' cells, and the samples of the tiles each decodes.
    const uint64_t across = uint64_t(std::max<int64_t>(1, c / steps) + 1);
    const uint64_t cells =
        chunks * ((side - 2) * (side - 2) + across * across * uint64_t(block_size) * block_size);
    const uint64_t shared = chunks * 4 * uint64_t(c) * kBytesPerNode;
    const int busy = int(std::min<uint64_t>(uint64_t(std::max(1, threads)), chunks));
    const uint64_t bytes = uint64_t(busy) * worker + shared;
    if (bytes <= memory_bytes && cells <= best_cells) best = c, best_cells = cells;
    if (bytes < cheapest_bytes) cheapest_bytes = bytes, cheapest = c;
  }
  if (best == 0) best = cheapest;
  return best;
}

FlowSolution solve_flow(const TerrainPackage& p, const FlowSettings& s, Progress& progress) {
  return Solver(p, s, progress).run();
}

}  // namespace globe::flow
