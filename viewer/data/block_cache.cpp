// Block cache and loader thread (see block_cache.hpp).
#include "data/block_cache.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "data/block_substitute.hpp"
#include "tileformat/analysis_block.hpp"
#include "tileformat/error.hpp"
#include "tileformat/kpatch.hpp"
#include "tileformat/mblock.hpp"
#include "tileformat/package.hpp"

namespace globe::viewer {

using tileformat::TileId;

namespace {

// A terrain blob as a grid of heights (metres) and its vertex errors.
SampleGrid height_grid(std::span<const uint8_t> blob, int block_size, int lattice,
                       std::vector<uint32_t>* vertex_error) {
  tileformat::MBlock b = tileformat::decode_mblock(blob);
  if (b.size != block_size || b.lattice != lattice)
    throw tileformat::FormatError("§5", "block size or lattice differs from the metadata");
  SampleGrid g;
  g.size = block_size;
  g.values.resize(b.q.size());
  g.mask.assign(b.q.size(), 255);
  for (size_t i = 0; i < b.q.size(); ++i) {
    g.values[i] = static_cast<float>(b.q[i] * b.step);
    if (!b.valid.empty() && !b.valid[i]) g.mask[i] = 0;
  }
  if (vertex_error) *vertex_error = std::move(b.vertex_error);
  return g;
}

// The analysis texels and flow texels of a block as one grid (4 +
// kFlowTexel channels).
SampleGrid analysis_grid(const tileformat::AnalysisBlock& b, int block_size) {
  const std::vector<float> texels = analysis_texels(b), flow = flow_texels(b);
  SampleGrid g;
  g.size = block_size;
  g.channels = 4 + kFlowTexel;
  const size_t n = size_t(block_size) * block_size;
  g.values.resize(n * g.channels);
  g.mask.assign(n, 255);
  for (size_t i = 0; i < n; ++i) {
    std::copy_n(texels.begin() + long(4 * i), 4, g.values.begin() + long(i * g.channels));
    std::copy_n(flow.begin() + long(kFlowTexel * i), kFlowTexel,
                g.values.begin() + long(i * g.channels + 4));
  }
  return g;
}

// The analysis grid of tile `id`; a tile the package lacks has no layers.
SampleGrid read_analysis_grid(const AnalysisSource& a, TileId id, int block_size) {
  const auto blob = a.reader->tile(id);
  tileformat::AnalysisBlock b;
  b.size = block_size;
  if (blob) {
    b = tileformat::decode_analysis_block(*blob);
    if (b.size != block_size)
      throw tileformat::FormatError("9", "block size differs from the terrain's");
  }
  return analysis_grid(b, block_size);
}

// What a stand-in is made of, for the warning.
const char* stand_name(Stand s) {
  return s == Stand::kChildren ? "drawing its children's samples there"
                               : "drawing its parent's samples there";
}

// Runs on the loader thread. A block that cannot be read is drawn from a
// stand-in (block_substitute.hpp) and reported once; so is its analysis.
auto decode_block(const TerrainPackage& pkg, const std::optional<AnalysisSource>& analysis) {
  const size_t errors =
      tileformat::kpatch_vertex_count(tileformat::kpatch_depth(pkg.block_size - 1, pkg.lattice));
  return [&pkg, &analysis, errors](TileId id, std::span<const uint8_t> blob) {
    DecodedBlock d;
    d.block.id = id;
    SampleGrid g;
    try {
      g = height_grid(blob, pkg.block_size, pkg.lattice, &d.meta.vertex_error);
    } catch (const std::exception& e) {
      SubstituteSource source{pkg.block_size, pkg.min_zoom, pkg.max_zoom, [&](TileId t) {
                                std::optional<SampleGrid> out;
                                if (pkg.tiling.contains(t))
                                  if (const auto b = pkg.reader->tile(t))
                                    out = height_grid(*b, pkg.block_size, pkg.lattice, nullptr);
                                return out;
                              }};
      auto [stand, from] = substitute_grid(source, id);
      if (!stand) throw;  // nothing to draw there: the tile stays broken
      g = std::move(*stand);
      // Its vertex errors are unknown: zero, and where it stands for its
      // children the selection splits through it to them.
      d.meta.vertex_error.assign(errors, 0);
      d.meta.split_through = from == Stand::kChildren;
      d.warning = std::string(e.what()) + "; " + stand_name(from);
    }
    const size_t n = g.values.size();
    d.block.heights = std::move(g.values);
    d.block.mask = std::move(g.mask);
    // Over all samples (a block's holes are filled), a stand-in's valid ones.
    const bool stand_in = !d.warning.empty();
    float lo = 0, hi = 0;
    bool any = false;
    for (size_t i = 0; i < n; ++i) {
      if (stand_in && !d.block.mask[i]) continue;
      const float h = d.block.heights[i];
      lo = any ? std::min(lo, h) : h;
      hi = any ? std::max(hi, h) : h;
      any = true;
    }
    d.meta.min_h = lo;
    d.meta.max_h = hi;
    if (analysis) {
      SampleGrid a;
      try {
        a = read_analysis_grid(*analysis, id, pkg.block_size);
      } catch (const std::exception& e) {
        SubstituteSource source{
            pkg.block_size, pkg.min_zoom, pkg.max_zoom, [&](TileId t) {
              return std::optional<SampleGrid>(read_analysis_grid(*analysis, t, pkg.block_size));
            }};
        auto [stand, from] = substitute_grid(source, id);
        if (stand) {
          a = std::move(*stand);
        } else {  // no analysis there: no layers' defaults
          tileformat::AnalysisBlock none;
          none.size = pkg.block_size;
          a = analysis_grid(none, pkg.block_size);
        }
        d.analysis_warning =
            std::string(e.what()) + "; " +
            (stand ? stand_name(from) : "drawing the terrain without its analysis there");
      }
      d.block.analysis.resize(n * 4);
      d.block.flow.resize(n * kFlowTexel);
      for (size_t i = 0; i < n; ++i) {
        std::copy_n(a.values.begin() + long(i * a.channels), 4,
                    d.block.analysis.begin() + long(4 * i));
        std::copy_n(a.values.begin() + long(i * a.channels + 4), kFlowTexel,
                    d.block.flow.begin() + long(kFlowTexel * i));
      }
    }
    return d;
  };
}

}  // namespace

BlockCache::BlockCache(const std::string& path, TerrainPackage package, uint64_t budget_bytes,
                       std::optional<AnalysisSource> analysis)
    : path_(path), package_(std::move(package)), analysis_(std::move(analysis)) {
  const uint64_t samples = uint64_t(package_.block_size) * package_.block_size;
  const size_t errors = tileformat::kpatch_vertex_count(
      tileformat::kpatch_depth(package_.block_size - 1, package_.lattice));
  bytes_per_slot_ = samples * (sizeof(float) + 1) + errors * sizeof(uint32_t) + 256;
  if (analysis_) bytes_per_slot_ += samples * 8;  // RGBA16F texels
  slots_ = std::max<uint64_t>(8, budget_bytes / bytes_per_slot_);
  stats_.slots = slots_;
  stats_.budget_bytes = budget_bytes;
  for (int s = static_cast<int>(slots_) - 1; s >= 0; --s)
    free_slots_.push_back(s);
  loader_ = std::make_unique<Loader>(*package_.reader, decode_block(package_, analysis_));
}

BlockCache::~BlockCache() = default;

BlockState BlockCache::state(TileId id) {
  if (id.z < package_.min_zoom || id.z > package_.max_zoom || !package_.tiling.contains(id))
    return BlockState::kAbsent;
  auto it = entries_.find(id);
  if (it != entries_.end()) return it->second.state;
  Entry e;
  e.state = package_.reader->has_tile(id) ? BlockState::kNotLoaded : BlockState::kAbsent;
  entries_.emplace(id, e);
  return e.state;
}

const ResidentBlock* BlockCache::use(TileId id) {
  auto it = entries_.find(id);
  if (it == entries_.end() || it->second.state != BlockState::kResident) return nullptr;
  it->second.block.last_used_frame = frame_;
  return &it->second.block;
}

void BlockCache::request(TileId id, double priority) {
  if (state(id) != BlockState::kNotLoaded) return;
  wanted_.emplace_back(priority, id);
}

int BlockCache::take_slot() {
  if (!free_slots_.empty()) {
    const int s = free_slots_.back();
    free_slots_.pop_back();
    return s;
  }
  // Evict the least recently used block that this frame does not draw.
  auto victim = entries_.end();
  for (auto it = entries_.begin(); it != entries_.end(); ++it)
    if (it->second.state == BlockState::kResident && it->second.block.last_used_frame < frame_ &&
        (victim == entries_.end() ||
         it->second.block.last_used_frame < victim->second.block.last_used_frame))
      victim = it;
  if (victim == entries_.end()) return -1;
  const int s = victim->second.block.slot;
  victim->second = Entry{};  // back to kNotLoaded
  ++stats_.evictions;
  --stats_.resident;
  return s;
}

void BlockCache::flush_requests() {
  std::sort(wanted_.begin(), wanted_.end(), [](const auto& a, const auto& b) {
    return a.first < b.first || (a.first == b.first && a.second < b.second);
  });
  std::vector<Loader::Job> jobs;
  for (const auto& [priority, id] : wanted_) {
    Entry& e = entries_[id];
    if (e.state != BlockState::kNotLoaded) continue;  // requested twice this frame
    const int slot = take_slot();
    if (slot < 0) break;  // the budget is full of blocks this frame draws
    e.state = BlockState::kLoading;
    jobs.push_back({id, slot});
  }
  wanted_.clear();
  loader_->submit(jobs);
}

std::vector<LoadedBlock> BlockCache::take_loaded() {
  std::vector<LoadedBlock> out;
  for (Loader::Done& d : loader_->take_done()) {
    const TileId id = d.job.id;
    const int slot = d.job.tag;
    Entry& e = entries_[id];
    stats_.bytes_read += d.bytes;
    if (d.absent) {
      e.state = BlockState::kAbsent;
      free_slots_.push_back(slot);
      continue;
    }
    if (!d.ok) {
      std::fprintf(stderr,
                   "globe-view: warning: %s: tile %s: %s; nothing to draw in its stead (no "
                   "readable children or parent)\n",
                   path_.c_str(), id.str().c_str(), d.error.c_str());
      e.state = BlockState::kBroken;
      free_slots_.push_back(slot);
      ++stats_.broken;
      continue;
    }
    // A stand-in (the tile itself is broken), or a broken analysis tile:
    // named once, however often the block is evicted and loaded again.
    for (const std::string* w : {&d.value.warning, &d.value.analysis_warning})
      if (!w->empty() && warned_.insert({id, w == &d.value.warning}).second) {
        std::fprintf(stderr, "globe-view: warning: %s: tile %s: %s\n",
                     w == &d.value.warning || !analysis_ ? path_.c_str() : analysis_->path.c_str(),
                     id.str().c_str(), w->c_str());
        if (w == &d.value.warning) ++stats_.broken;
      }
    e.state = BlockState::kResident;
    e.block = std::move(d.value.meta);
    e.block.slot = slot;
    e.block.last_used_frame = frame_;
    ++stats_.blocks_loaded;
    ++stats_.resident;
    d.value.block.slot = slot;
    out.push_back(std::move(d.value.block));
  }
  return out;
}

CacheStats BlockCache::stats() const {
  CacheStats s = stats_;
  s.resident_bytes = s.resident * bytes_per_slot_;
  return s;
}

std::vector<std::pair<TileId, int>> BlockCache::resident_slots() const {
  std::vector<std::pair<TileId, int>> out;
  for (const auto& [id, e] : entries_)
    if (e.state == BlockState::kResident) out.emplace_back(id, e.block.slot);
  return out;
}

}  // namespace globe::viewer
