// The out-of-core flow solver (see flow_solver.hpp).
#include "analysis/flow/flow_solver.hpp"

#include <algorithm>
#include <bit>
#include <map>

#include "analysis/batch_blocks.hpp"
#include "analysis/flow/chunk_heights.hpp"
#include "analysis/flow/depression_fill.hpp"
#include "analysis/flow/depression_routing.hpp"
#include "analysis/flow/flow_accumulation.hpp"
#include "analysis/flow/flow_directions.hpp"
#include "analysis/flow/least_cost_routing.hpp"
#include "kit/parallel_batches.hpp"
#include "kit/scratch_array_file.hpp"
#include "runtime/errors.hpp"

namespace globe::flow {

namespace {

// Bytes a worker holds per chunk cell at the busiest pass (the directions:
// filled heights read back and windowed, distances and keys, the flat
// cells' queue, receivers, areas, Kahn's order and links).
constexpr uint64_t kBytesPerCell = 60;
// Bytes per perimeter cell at the busiest moment of the run (the perimeter
// graph's solve; the watershed graph's edges are deduplicated per chunk).
constexpr uint64_t kBytesPerNode = 64;
// Scratch bytes per grid cell at the busiest pass (the directions): filled
// and raw heights 8, flat distances and keys 8, depression receivers and D8
// receivers 1 each. The watersheds (4) go before the flats come; the
// pyramid's levels (about 12 a cell) once the heights and flats are gone.
constexpr uint64_t kScratchBytesPerCell = 18;

// Bytes per window cell of the whole grid solved as one chunk (alone) at
// its busiest, the directions: raw and filled heights 8, flat distances and
// keys 8, receivers 1, the depression search's state 1, and the flat
// cells' lists (measured: 21 a cell on the synthetic 4096^2 DEM).
constexpr uint64_t kAloneBytesPerCell = 24;

// The memory a run with chunks of C cells a side holds at its busiest
// moment, scratch aside: the workers' chunks (each with the blocks it
// decodes) and the perimeters kept for the whole run.
uint64_t working_bytes(int64_t c, int64_t whole, int block_size, uint64_t chunks, int threads) {
  const int64_t steps = block_size - 1;
  const uint64_t side = uint64_t(std::min(c, whole) + 2);
  const uint64_t tiles = uint64_t(c / steps + 3) * uint64_t(c / steps + 3);
  const uint64_t worker = side * side * kBytesPerCell + tiles * block_size * block_size * 5;
  const uint64_t shared = chunks * 4 * uint64_t(c) * kBytesPerNode;
  const int busy = int(std::min<uint64_t>(uint64_t(std::max(1, threads)), chunks));
  return uint64_t(busy) * worker + shared;
}

using tileformat::TileId;

struct Perimeters {            // per node (perimeter cell of a chunk), in slot order
  std::vector<uint64_t> base;  // per slot: its first node
  std::vector<int32_t> height, filled, raw;
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
    const int64_t c = s_.chunk > 0 ? s_.chunk
                                   : chunk_size_for(p_.tiling, p_.max_zoom, p_.block_size, finest,
                                                    s_.memory_bytes, s_.threads);
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
    // The scratch arrays stay in memory where they fit the budget beside
    // the workers' chunks (a single chunk has room for them: kBytesPerCell).
    const uint64_t cells = cell_base_.back();
    const int64_t whole =
        int64_t(std::max(g.tiling().tiles_x(g.zoom()), g.tiling().tiles_y(g.zoom()))) * g.steps();
    in_memory_ =
        chunks.size() == 1 || working_bytes(c, whole, p_.block_size, chunks.size(), s_.threads) +
                                      cells * kScratchBytesPerCell <=
                                  s_.memory_bytes;
    out_.scratch_in_memory = in_memory_;
    if (alone()) {
      solve_alone();
      out_.pyramid->finish();
      return std::move(out_);
    }
    fill_ = std::make_unique<ScratchArrayFile>(s_.scratch_prefix + "fill.bin", memory(cells * 8));
    labels_ =
        std::make_unique<ScratchArrayFile>(s_.scratch_prefix + "watersheds.bin", memory(cells * 4));
    fill_pass();
    route_flats();
    deps_ =
        std::make_unique<ScratchArrayFile>(s_.scratch_prefix + "depressions.bin", memory(cells));
    route_depressions();
    dirs_ = std::make_unique<ScratchArrayFile>(s_.scratch_prefix + "receivers.bin", memory(cells));
    accumulate();
    dirs_.reset();
    out_.pyramid->finish();
    return std::move(out_);
  }

 private:
  const FlowGrid& grid() const { return *out_.grid; }
  std::optional<uint64_t> memory(uint64_t bytes) const {
    return in_memory_ ? std::optional<uint64_t>(bytes) : std::nullopt;
  }
  void start_pyramid() {
    out_.pyramid =
        std::make_unique<FlowPyramid>(grid(), p_.min_zoom, s_.scratch_prefix, in_memory_);
  }
  // A single chunk that does not wrap: nothing comes from outside it.
  bool alone() const { return grid().chunks().size() == 1 && !grid().wraps(); }
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

  // ---- The whole grid as one chunk that does not wrap (alone): nothing
  // comes from outside it, so each pass runs once on its window, in turn,
  // with no watersheds, flat rounds, perimeters or scratch; the blocks are
  // decoded one at a time. The same answer as the chunked passes below.
  void solve_alone() {
    const FlowGrid& g = grid();
    const Chunk& c = chunk(0);
    out_.watersheds = 1;  // the data's edge
    start_pyramid();
    std::vector<uint8_t> codes;
    {
      HeightPatch p;
      p.x0 = c.x0 - 1, p.y0 = c.y0 - 1, p.w = c.w + 2, p.h = c.h + 2;
      progress_.begin("flow: fill depressions", 1);
      {
        BatchBlocks one;
        p.raw = chunk_heights(g, c, [&](TileId t) {
          one = BatchBlocks();
          one.add(t, p_.reader->tile(t));
          return one.get(t, s_.input);
        });
      }
      p.filled = filled_surface(c, p.raw);
      progress_.advance();
      progress_.end();
      progress_.begin("flow: directions", 1);
      std::vector<uint32_t> d(p.filled.size(), kFar);
      std::vector<int32_t> key(d.size(), kNoKey);
      flat_distances(c, p.filled, d, key);
      codes = d8_receivers(g, c, p.filled, d, key);
      route_window_depressions(
          0, p, d, key, [&](size_t i, uint8_t code) { codes[i] = code; }, nullptr);
      progress_.advance();
      progress_.end();
    }
    progress_.begin("flow: accumulate", 1);
    LevelGrid level;
    level.x0 = c.x0, level.y0 = c.y0, level.w = c.w, level.h = c.h;
    level.area = accumulate_chunk(g, c, codes, {}, nullptr);
    level.code = std::move(codes);
    out_.pyramid->put_chunk(0, std::move(level));
    progress_.advance();
    progress_.end();
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
          const uint64_t at = cell_base_[size_t(slot)];
          write_rows(*fill_, at * 8, c, f.filled);
          write_rows(*fill_, at * 8 + c.cells() * 4, c, z);
          write_rows(*labels_, at * 4, c, f.label);
          FillResult r;
          for (int i = 0; i < c.perimeter_count(); ++i) {
            int x, y;
            c.perimeter_cell(i, x, y);
            r.height.push_back(z[ChunkWindow(c).at(x, y)]);
            r.label.push_back(f.label[ChunkWindow(c).at(x, y)]);
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
    // Perimeter cells keep their raw and filled heights and watershed.
    per_.raw = per_.height;
    per_.filled = std::move(per_.height);
    for (size_t n = 0; n < nodes; ++n)
      if (per_.filled[n] != kNoData)
        per_.filled[n] = std::max(per_.filled[n], spill_[per_.label[n]]);
    raise_to_spill_levels();
  }

  // Each chunk's filled heights raised to its watersheds' spill levels, in
  // place: the later passes read the final surface, and the watersheds go.
  void raise_to_spill_levels() {
    each_chunk<int>(
        "flow: spill levels", all_slots(),
        [&](int slot, const BatchBlocks&) {
          const Chunk& c = chunk(slot);
          const uint64_t at = cell_base_[size_t(slot)];
          std::vector<int32_t> filled(c.cells());
          std::vector<uint32_t> label(c.cells());
          fill_->read_array<int32_t>(at * 8, filled);
          labels_->read_array<uint32_t>(at * 4, label);
          for (size_t i = 0; i < filled.size(); ++i)
            if (filled[i] != kNoData)
              filled[i] = std::max(filled[i], spill_[global_label(slot, label[i])]);
          fill_->write_array<int32_t>(at * 8, filled);
          return 0;
        },
        [](int, int&&) {}, false);
    labels_.reset();
  }

  // A chunk's rows between a scratch array (row-major, from `at`) and its
  // window (ChunkWindow), each way.
  template <typename T>
  static void write_rows(ScratchArrayFile& file, uint64_t at, const Chunk& c,
                         const std::vector<T>& window) {
    const ChunkWindow win(c);
    file.write_rows_at(at, window.data() + win.at(0, 0), size_t(c.w) * sizeof(T), size_t(c.h),
                       size_t(win.stride()) * sizeof(T));
  }
  template <typename T>
  static void read_rows(const ScratchArrayFile& file, uint64_t at, const Chunk& c,
                        std::vector<T>& window) {
    const ChunkWindow win(c);
    file.read_rows_at(at, window.data() + win.at(0, 0), size_t(c.w) * sizeof(T), size_t(c.h),
                      size_t(win.stride()) * sizeof(T));
  }

  uint32_t global_label(int slot, uint32_t local) const {
    return local == kEdgeLabel ? 0 : uint32_t(label_base_[size_t(slot)] + local - 2);
  }

  // The filled heights (the whole grid's) and raw heights of the chunk's
  // rows `first` to `last` - 1, row-major.
  void read_chunk(int slot, std::vector<int32_t>& filled, std::vector<int32_t>& raw, int first,
                  int last) const {
    const Chunk& c = chunk(slot);
    const size_t n = size_t(last - first) * c.w;
    const uint64_t at = cell_base_[size_t(slot)] * 8 + uint64_t(first) * c.w * 4;
    filled.resize(n);
    raw.resize(n);
    fill_->read_array<int32_t>(at, filled);
    fill_->read_array<int32_t>(at + c.cells() * 4, raw);
  }

  // The chunk's window of filled heights (and of raw heights).
  std::vector<int32_t> filled_window(int slot, const std::vector<int64_t>& ring,
                                     std::vector<int32_t>* raw_window = nullptr) const {
    const Chunk& c = chunk(slot);
    const ChunkWindow win(c);
    const uint64_t at = cell_base_[size_t(slot)] * 8;
    std::vector<int32_t> f(win.size(), kNoData);
    read_rows(*fill_, at, c, f);
    if (raw_window) {
      raw_window->assign(win.size(), kNoData);
      read_rows(*fill_, at + c.cells() * 4, c, *raw_window);
    }
    put_ring(c, f, ring, [&](int64_t n) { return n < 0 ? kNoData : per_.filled[size_t(n)]; });
    if (raw_window)
      put_ring(c, *raw_window, ring,
               [&](int64_t n) { return n < 0 ? kNoData : per_.raw[size_t(n)]; });
    return f;
  }

  // The chunk's windows of flat distances and keys.
  void flat_windows(int slot, const std::vector<int64_t>& ring, const std::vector<int32_t>& f,
                    std::vector<uint32_t>& d, std::vector<int32_t>& key) const {
    if (flats_settled_) return stored_flat_windows(slot, ring, d, key);
    ring_flat_windows(chunk(slot), ring, d, key);
    flat_distances(chunk(slot), f, d, key);
  }

  // Windows holding the ring's distances and keys as they stand (the
  // chunk's own cells unknown).
  void ring_flat_windows(const Chunk& c, const std::vector<int64_t>& ring, std::vector<uint32_t>& d,
                         std::vector<int32_t>& key) const {
    d.assign(ChunkWindow(c).size(), kFar);
    key.assign(d.size(), kNoKey);
    put_ring(c, d, ring, [&](int64_t n) { return n < 0 ? kFar : per_.distance[size_t(n)]; });
    put_ring(c, key, ring, [&](int64_t n) { return n < 0 ? kNoKey : per_.key[size_t(n)]; });
  }

  // The ring's distances and keys as they stand, the chunk's own as its
  // last flat round left them.
  void stored_flat_windows(int slot, const std::vector<int64_t>& ring, std::vector<uint32_t>& d,
                           std::vector<int32_t>& key) const {
    const Chunk& c = chunk(slot);
    const ChunkWindow win(c);
    ring_flat_windows(c, ring, d, key);
    read_rows(*flats_, cell_base_[size_t(slot)] * 8, c, d);
    read_rows(*flats_, cell_base_[size_t(slot)] * 8 + c.cells() * 4, c, key);
  }

  // A later flat round: only the flats next to ring cells whose distance or
  // key changed in the last round are solved again. A flat's distances and
  // keys depend on nothing but its cells and the known cells around it, and
  // a chunk runs again whenever one of those changed (ring_changed_on_flat),
  // so the others hold what solving them again would give.
  void refreshed_flat_windows(int slot, const std::vector<int64_t>& ring,
                              const std::vector<int32_t>& f, std::vector<uint32_t>& d,
                              std::vector<int32_t>& key) const {
    const Chunk& c = chunk(slot);
    stored_flat_windows(slot, ring, d, key);
    std::vector<uint8_t> changed(d.size(), 0);
    put_ring(c, changed, ring,
             [&](int64_t n) { return uint8_t(n >= 0 && per_.changed[size_t(n)]); });
    const std::vector<uint32_t> flats = flats_next_to(c, f, d, changed);
    for (uint32_t k : flats)
      d[k] = kFar, key[k] = kNoKey;
    settle_flats(c, f, d, key, flats);
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
    std::vector<int> run = all_slots();
    // Each chunk's distances and keys as its latest round left them: a chunk
    // not run again saw no change, so they are final for the later passes.
    flats_ = std::make_unique<ScratchArrayFile>(s_.scratch_prefix + "flats.bin",
                                                memory(cell_base_.back() * 8));
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
            if (out_.flat_rounds == 1)
              flat_windows(slot, ring, f, d, key);
            else
              refreshed_flat_windows(slot, ring, f, d, key);
            write_rows(*flats_, cell_base_[size_t(slot)] * 8, c, d);
            write_rows(*flats_, cell_base_[size_t(slot)] * 8 + c.cells() * 4, c, key);
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
    flats_settled_ = true;
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

  // ---- 4: depressions (depression_routing.hpp) ----
  // A depression's cells in one chunk, where the depression crosses the
  // chunk's edge.
  struct DepressionPart {
    std::vector<int> perimeter;  // its perimeter cells (indices)
    bool has_entry = false;
    EntryRank entry{};  // the least of its rim cells next to this chunk's cells
    int64_t x_min = 0, x_max = 0, y_min = 0, y_max = 0, seed_x = 0, seed_y = 0;
  };

  // The chunk's window as a patch: filled heights, and raw ones `with_raw`.
  HeightPatch window_patch(int slot, const std::vector<int64_t>& ring, bool with_raw) const {
    const Chunk& c = chunk(slot);
    HeightPatch p;
    p.x0 = c.x0 - 1, p.y0 = c.y0 - 1, p.w = c.w + 2, p.h = c.h + 2;
    p.filled = filled_window(slot, ring, with_raw ? &p.raw : nullptr);
    return p;
  }

  // Routes the depressions of the chunk's window that lie inside the chunk
  // (out(chunk index, code)); with `parts`, notes those that cross its edge.
  template <typename Out>
  void route_window_depressions(int slot, const HeightPatch& p, const std::vector<uint32_t>& d,
                                const std::vector<int32_t>& key, Out out,
                                std::vector<DepressionPart>* parts) const {
    const Chunk& c = chunk(slot);
    const ChunkWindow win(c);
    DepressionRouter router(p);
    auto in_chunk = [&](uint32_t i) {
      const int x = int(i % uint32_t(p.w)), y = int(i / uint32_t(p.w));
      return x > 0 && y > 0 && x <= c.w && y <= c.h;
    };
    for (int y = 0; y < c.h; ++y)
      for (int x = 0; x < c.w; ++x) {
        const uint32_t i = uint32_t(win.at(x, y));
        if (!p.in_depression(i) || router.seen(i)) continue;
        bool crosses = false;
        const std::vector<uint32_t> cells = router.depression(i, crosses);
        EntryRank rank;
        uint32_t entry = 0;
        const bool has_entry = depression_entry(grid(), p, cells, d, key, in_chunk, rank, entry);
        if (!crosses) {
          if (has_entry)
            router.route(grid(), cells, entry, [&](uint32_t k, uint8_t code) {
              out(size_t(k / uint32_t(p.w) - 1) * c.w + (k % uint32_t(p.w) - 1), code);
            });
          continue;
        }
        if (!parts) continue;
        DepressionPart part;
        part.has_entry = has_entry;
        part.entry = rank;
        part.seed_x = c.x0 + x, part.seed_y = c.y0 + y;
        part.x_min = part.x_max = part.seed_x, part.y_min = part.y_max = part.seed_y;
        for (uint32_t k : cells) {
          if (!in_chunk(k)) continue;
          const int cx = int(k % uint32_t(p.w)) - 1, cy = int(k / uint32_t(p.w)) - 1;
          part.x_min = std::min(part.x_min, c.x0 + cx),
          part.x_max = std::max(part.x_max, c.x0 + cx);
          part.y_min = std::min(part.y_min, c.y0 + cy),
          part.y_max = std::max(part.y_max, c.y0 + cy);
          const int pi = c.perimeter_index(cx, cy);
          if (pi >= 0) part.perimeter.push_back(pi);
        }
        parts->push_back(std::move(part));
      }
  }

  // Each chunk routes the depressions inside it and notes the parts of those
  // that cross its edge; these are joined across chunks, gathered whole and
  // routed (the receivers go to the depressions scratch file, 0 elsewhere).
  void route_depressions() {
    std::vector<std::vector<DepressionPart>> parts(grid().chunks().size());
    each_chunk<std::vector<DepressionPart>>(
        "flow: depressions", all_slots(),
        [&](int slot, const BatchBlocks&) {
          const Chunk& c = chunk(slot);
          const std::vector<int64_t> ring = ring_nodes(c);
          const HeightPatch p = window_patch(slot, ring, true);
          std::vector<uint32_t> d;
          std::vector<int32_t> key;
          flat_windows(slot, ring, p.filled, d, key);
          std::vector<uint8_t> codes(c.cells(), 0);
          std::vector<DepressionPart> crossing;
          route_window_depressions(
              slot, p, d, key, [&](size_t i, uint8_t code) { codes[i] = code; }, &crossing);
          deps_->write_array<uint8_t>(cell_base_[size_t(slot)], codes);
          return crossing;
        },
        [&](int slot, std::vector<DepressionPart>&& r) { parts[size_t(slot)] = std::move(r); },
        false);
    join_depressions(parts);
  }

  // Depressions across chunk edges: parts joined where their perimeter cells
  // touch (union-find), then each routed from the least entry of its parts
  // over a patch of its bounding box. Those across the east-west wrap, or
  // with a bounding box over kMaxGatheredCells, keep the flat routing: a
  // fixed bound (the answer must not depend on --memory-mb), so gathering
  // holds at most about 60 MB beyond the budget.
  static constexpr uint64_t kMaxGatheredCells = uint64_t(1) << 22;

  void join_depressions(const std::vector<std::vector<DepressionPart>>& parts) {
    const FlowGrid& g = grid();
    std::vector<size_t> first(parts.size() + 1, 0);
    for (size_t k = 0; k < parts.size(); ++k)
      first[k + 1] = first[k] + parts[k].size();
    const size_t count = first.back();
    if (count == 0) return;
    std::vector<int64_t> part_of(per_.base.back(), -1);
    for (size_t k = 0; k < parts.size(); ++k)
      for (size_t j = 0; j < parts[k].size(); ++j)
        for (int i : parts[k][j].perimeter)
          part_of[size_t(per_.node(int(k), i))] = int64_t(first[k] + j);
    std::vector<size_t> up(count);
    for (size_t i = 0; i < count; ++i)
      up[i] = i;
    auto root = [&](size_t i) {
      while (up[i] != i)
        i = up[i] = up[up[i]];
      return i;
    };
    std::vector<uint8_t> seam(count, 0);
    for (size_t k = 0; k < parts.size(); ++k) {
      const Chunk& c = chunk(int(k));
      for (size_t j = 0; j < parts[k].size(); ++j)
        for (int i : parts[k][j].perimeter) {
          int x, y;
          c.perimeter_cell(i, x, y);
          for (int d = 1; d <= 8; ++d) {
            const int nx = x + kDx[d], ny = y + kDy[d];
            if (nx >= 0 && ny >= 0 && nx < c.w && ny < c.h) continue;
            const int64_t gx = c.x0 + nx;
            const int64_t m = node_at(gx, c.y0 + ny);
            if (m < 0 || part_of[size_t(m)] < 0) continue;
            const size_t a = root(first[k] + j), b = root(size_t(part_of[size_t(m)]));
            if (gx < 0 || gx >= g.width()) seam[a] = seam[b] = 1;
            if (a != b) {
              up[std::max(a, b)] = std::min(a, b);
              seam[std::min(a, b)] |= seam[std::max(a, b)];
            }
          }
        }
    }
    // Per depression (its root part, the least index): the union of its parts.
    std::vector<DepressionPart> whole(count);
    std::vector<uint8_t> joined(count, 0);
    for (size_t k = 0; k < parts.size(); ++k)
      for (size_t j = 0; j < parts[k].size(); ++j) {
        const DepressionPart& q = parts[k][j];
        const size_t r = root(first[k] + j);
        seam[r] |= seam[first[k] + j];
        DepressionPart& w = whole[r];
        if (!joined[r]) {
          w = q;
          joined[r] = 1;
          continue;
        }
        if (q.has_entry && (!w.has_entry || q.entry < w.entry)) w.entry = q.entry;
        w.has_entry |= q.has_entry;
        w.x_min = std::min(w.x_min, q.x_min), w.x_max = std::max(w.x_max, q.x_max);
        w.y_min = std::min(w.y_min, q.y_min), w.y_max = std::max(w.y_max, q.y_max);
      }
    for (size_t r = 0; r < count; ++r) {
      if (root(r) != r || seam[r] || !whole[r].has_entry) continue;
      const DepressionPart& w = whole[r];
      HeightPatch p;
      p.x0 = w.x_min - 1, p.y0 = w.y_min - 1;
      p.w = int(w.x_max - w.x_min + 3), p.h = int(w.y_max - w.y_min + 3);
      if (uint64_t(p.w) * uint64_t(p.h) > kMaxGatheredCells) continue;
      gather(p);
      const int64_t entry =
          patch_index(p, std::get<2>(w.entry) % g.width(), std::get<2>(w.entry) / g.width());
      if (entry < 0) continue;  // (it lies next to the depression: never)
      DepressionRouter router(p);
      bool crosses = false;
      const std::vector<uint32_t> cells =
          router.depression(uint32_t((w.seed_y - p.y0) * p.w + (w.seed_x - p.x0)), crosses);
      // Written per chunk it covers (the codes of all depressions together
      // could be a good part of the grid).
      std::map<int, std::vector<std::pair<uint32_t, uint8_t>>> codes;
      router.route(g, cells, uint32_t(entry), [&](uint32_t i, uint8_t code) {
        const int64_t x = p.x0 + i % uint32_t(p.w), y = p.y0 + i / uint32_t(p.w);
        const int slot = g.slot_of(x, y);
        const Chunk& c = chunk(slot);
        codes[slot].push_back({uint32_t((y - c.y0) * c.w + (x - c.x0)), code});
      });
      for (const auto& [slot, list] : codes) {
        std::vector<uint8_t> chunk_codes(chunk(slot).cells());
        deps_->read_array<uint8_t>(cell_base_[size_t(slot)], chunk_codes);
        for (const auto& [i, code] : list)
          chunk_codes[i] = code;
        deps_->write_array<uint8_t>(cell_base_[size_t(slot)], chunk_codes);
      }
    }
  }

  // Fills a patch from the chunks it overlaps (columns wrapped where the
  // grid wraps; no data off the grid).
  void gather(HeightPatch& p) const {
    const FlowGrid& g = grid();
    p.raw.assign(size_t(p.w) * p.h, kNoData);
    p.filled.assign(p.raw.size(), kNoData);
    std::vector<int64_t> column(size_t(p.w));
    for (int x = 0; x < p.w; ++x) {
      int64_t gx = p.x0 + x;
      column[size_t(x)] = g.normalise(gx, 0) ? gx : -1;
    }
    std::vector<int32_t> filled, raw;
    for (size_t k = 0; k < g.chunks().size(); ++k) {
      const Chunk& c = chunk(int(k));
      const int64_t y0 = std::max(p.y0, c.y0), y1 = std::min(p.y0 + p.h, c.y0 + c.h);
      auto mine = [&](int64_t gx) { return gx >= c.x0 && gx < c.x0 + c.w; };
      if (y0 >= y1 || std::none_of(column.begin(), column.end(), mine)) continue;
      // Only the rows the patch covers.
      read_chunk(int(k), filled, raw, int(y0 - c.y0), int(y1 - c.y0));
      for (int64_t y = y0; y < y1; ++y)
        for (int x = 0; x < p.w; ++x) {
          if (!mine(column[size_t(x)])) continue;
          const size_t from = size_t((y - y0) * c.w + (column[size_t(x)] - c.x0));
          const size_t to = size_t(y - p.y0) * p.w + x;
          p.filled[to] = filled[from];
          p.raw[to] = raw[from];
        }
    }
  }

  // The patch index of grid cell (x, y) (x normalised), or -1.
  int64_t patch_index(const HeightPatch& p, int64_t x, int64_t y) const {
    for (int64_t shift : {int64_t(0), -grid().width(), grid().width()}) {
      const int64_t px = x + shift - p.x0, py = y - p.y0;
      if (px >= 0 && py >= 0 && px < p.w && py < p.h) return py * p.w + px;
      if (!grid().wraps()) break;
    }
    return -1;
  }

  // ---- 5, 6, 7: receivers, accumulation ----
  struct LinkResult {
    PerimeterFlow flow;
    std::vector<int64_t> target;  // per perimeter cell: the node it drains into, or -1
  };

  void accumulate() {
    const size_t nodes = per_.base.back();
    std::vector<uint64_t> area(nodes, 0);
    std::vector<int64_t> successor(nodes, kNoNode);
    std::vector<uint8_t> crosses(nodes, 0);
    each_chunk<LinkResult>(
        "flow: directions", all_slots(),
        [&](int slot, const BatchBlocks&) {
          const Chunk& c = chunk(slot);
          // The windows go before the accumulation's arrays come.
          const std::vector<uint8_t> rec = [&] {
            const std::vector<int64_t> ring = ring_nodes(c);
            const std::vector<int32_t> f = filled_window(slot, ring);
            std::vector<uint32_t> d;
            std::vector<int32_t> key;
            flat_windows(slot, ring, f, d, key);
            std::vector<uint8_t> codes = d8_receivers(grid(), c, f, d, key);
            std::vector<uint8_t> routed(c.cells());
            deps_->read_array<uint8_t>(cell_base_[size_t(slot)], routed);
            for (size_t i = 0; i < routed.size(); ++i)
              if (routed[i]) codes[i] = routed[i];
            return codes;
          }();
          LinkResult r;
          accumulate_chunk(grid(), c, rec, {}, &r.flow);
          dirs_->write_array<uint8_t>(cell_base_[size_t(slot)], rec);
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
    deps_.reset();
    flats_.reset();
    Perimeters kept;
    kept.base = std::move(per_.base);
    per_ = std::move(kept);
    std::vector<int32_t>().swap(spill_);
    // Started only now, the pyramid's levels replace the scratch just freed.
    start_pyramid();
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
  // Scratch, per cell: filled and raw heights; watersheds (until the spill
  // levels are known); flat distances and keys; depression receivers; D8
  // receivers.
  std::unique_ptr<ScratchArrayFile> fill_, labels_, flats_, deps_, dirs_;
  bool flats_settled_ = false;  // flats_ holds every chunk's final distances and keys
  bool in_memory_ = false;      // the scratch arrays in memory, not in files
};

}  // namespace

int64_t chunk_size_for(const tileformat::Tiling& t, int zoom, int block_size,
                       const std::vector<TileId>& finest, uint64_t memory_bytes, int threads) {
  const int64_t steps = block_size - 1;
  const int64_t cols = int64_t(t.tiles_x(zoom)) * steps, rows = int64_t(t.tiles_y(zoom)) * steps;
  const int64_t whole = std::max(cols, rows);
  // The whole grid in one chunk that does not wrap, where it fits: each
  // pass runs once, with nothing to join (the least work, one thread).
  const int64_t one = std::bit_ceil(uint64_t(whole));
  const uint64_t window = uint64_t(cols + 2) * uint64_t(rows + 2);
  if (!t.wrap_tiles() && window * kAloneBytesPerCell <= memory_bytes)
    return std::max<int64_t>(one, 64);
  // Workers' chunks grow with C, the perimeters kept for the whole run
  // shrink: the largest C that fits, else the cheapest.
  int64_t best = 0, cheapest = 64;
  uint64_t cheapest_bytes = UINT64_MAX, best_cells = UINT64_MAX;
  for (int64_t c = 64; c < 2 * whole; c *= 2) {
    const uint64_t side = uint64_t(std::min(c, whole) + 2);
    int64_t cx = 0, cy = 0;
    const std::vector<uint8_t> present =
        FlowGrid::present_chunks(t, zoom, int(steps), finest, c, cx, cy);
    const uint64_t chunks =
        std::max<uint64_t>(1, uint64_t(std::count(present.begin(), present.end(), 1)));
    // Cost: the chunks' cells, and the samples of the tiles each decodes.
    const uint64_t across = uint64_t(std::max<int64_t>(1, c / steps) + 1);
    const uint64_t cells =
        chunks * ((side - 2) * (side - 2) + across * across * uint64_t(block_size) * block_size);
    const uint64_t bytes = working_bytes(c, whole, block_size, chunks, threads);
    if (bytes <= memory_bytes && cells <= best_cells) best = c, best_cells = cells;
    if (bytes < cheapest_bytes) cheapest_bytes = bytes, cheapest = c;
  }
  if (best == 0) best = cheapest;
  return best;
}

namespace {

// Calls fn(chunk cell, window cell) for each cell of chunk k inside the
// window (runs of a row are contiguous in both, so the wrap is worked out
// once per row).
template <typename F>
void for_window_cells(const FlowGrid& g, const GridWindow& win, const Chunk& k, F fn) {
  for (int y = 0; y < k.h; ++y) {
    const int64_t first = win.local(g, k.x0, k.y0 + y);
    if (first >= 0 && first % win.w + k.w <= win.w) {  // the whole row, one run
      for (int x = 0; x < k.w; ++x)
        fn(size_t(y) * k.w + x, size_t(first + x));
      continue;
    }
    for (int x = 0; x < k.w; ++x) {
      const int64_t i = win.local(g, k.x0 + x, k.y0 + y);
      if (i >= 0) fn(size_t(y) * k.w + x, size_t(i));
    }
  }
}

// --flow-method carve: the data's window of the grid routed by least cost
// in memory (its heights read chunk by chunk), then cut into the chunks of
// the fill method's grid for the pyramid.
FlowSolution solve_carved(const TerrainPackage& p, const FlowSettings& s, Progress& progress) {
  const std::vector<TileId> finest = p.reader->tile_ids(p.max_zoom);
  const int64_t c = s.chunk > 0 ? s.chunk
                                : chunk_size_for(p.tiling, p.max_zoom, p.block_size, finest,
                                                 s.memory_bytes, s.threads);
  FlowSolution out;
  out.method = FlowMethod::kCarve;
  out.scratch_in_memory = true;
  out.grid = std::make_unique<FlowGrid>(p.tiling, p.max_zoom, p.block_size, finest, c);
  const FlowGrid& g = *out.grid;
  const GridWindow win = GridWindow::of_tiles(g, finest);
  const uint64_t need_mb = (win.cells() * kCarveBytesPerCell >> 20) + 1;
  if (need_mb > s.memory_bytes >> 20 || win.cells() >= UINT32_MAX)
    throw UsageError("--flow-method carve holds the data's part of the finest zoom of " + s.input +
                     " in memory: " + std::to_string(win.w) + " x " + std::to_string(win.h) +
                     " cells need about " + std::to_string(need_mb) +
                     " MB, more than --memory-mb " + std::to_string(s.memory_bytes >> 20) +
                     "; raise --memory-mb, or use --flow-method fill (solved out of core)");
  std::vector<int32_t> z(size_t(win.cells()), kNoData);
  progress.begin("flow: read heights", g.chunks().size());
  for (const Chunk& k : g.chunks()) {
    BatchBlocks one;
    const std::vector<int32_t> heights =
        ChunkWindow(k).take_cells(chunk_heights(g, k, [&](TileId t) {
          one = BatchBlocks();
          one.add(t, p.reader->tile(t));
          return one.get(t, s.input);
        }));
    for_window_cells(g, win, k, [&](size_t chunk_cell, size_t window_cell) {
      z[window_cell] = heights[chunk_cell];
    });
    progress.advance();
  }
  progress.end();
  progress.begin("flow: least-cost routing", 1);
  const CarvedFlow carved = route_least_cost(g, win, z);
  std::vector<int32_t>().swap(z);
  progress.advance();
  progress.end();
  out.pyramid = std::make_unique<FlowPyramid>(g, p.min_zoom, s.scratch_prefix, true);
  for (size_t slot = 0; slot < g.chunks().size(); ++slot) {
    const Chunk& k = g.chunks()[slot];
    LevelGrid level;
    level.x0 = k.x0, level.y0 = k.y0, level.w = k.w, level.h = k.h;
    level.area.assign(k.cells(), 0);
    level.code.assign(k.cells(), kNoDataCode);
    for_window_cells(g, win, k, [&](size_t chunk_cell, size_t window_cell) {
      level.area[chunk_cell] = carved.area[window_cell];
      level.code[chunk_cell] = carved.code[window_cell];
    });
    out.pyramid->put_chunk(int(slot), std::move(level));
  }
  out.pyramid->finish();
  return out;
}

}  // namespace

FlowSolution solve_flow(const TerrainPackage& p, const FlowSettings& s, Progress& progress) {
  if (s.method == FlowMethod::kCarve) return solve_carved(p, s, progress);
  return Solver(p, s, progress).run();
}

}  // namespace globe::flow
