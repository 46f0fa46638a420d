// Block cache and loader thread (see block_cache.hpp).
#include "data/block_cache.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "tileformat/analysis_block.hpp"
#include "tileformat/error.hpp"
#include "tileformat/kpatch.hpp"
#include "tileformat/mblock.hpp"
#include "tileformat/package.hpp"

namespace globe::viewer {

using tileformat::TileId;

namespace {

// The analysis block of tile `id` (no layers where the package has no tile).
tileformat::AnalysisBlock read_analysis(const AnalysisSource& a, TileId id, int block_size) {
  const auto blob = a.reader->tile(id);
  tileformat::AnalysisBlock b;
  if (blob) {
    try {
      b = tileformat::decode_analysis_block(*blob);
    } catch (const tileformat::FormatError& e) {
      throw std::runtime_error(a.path + ": " + e.what());
    }
    if (b.size != block_size)
      throw tileformat::FormatError("9", a.path + ": block size differs from the terrain's");
  } else {
    b.size = block_size;
  }
  return b;
}

// Runs on the loader thread.
auto decode_block(int block_size, int lattice, const std::optional<AnalysisSource>& analysis) {
  return [block_size, lattice, &analysis](TileId id, std::span<const uint8_t> blob) {
    tileformat::MBlock b = tileformat::decode_mblock(blob);
    if (b.size != block_size || b.lattice != lattice)
      throw tileformat::FormatError("§5", "block size or lattice differs from the metadata");
    const size_t n = b.q.size();
    DecodedBlock d;
    d.block.id = id;
    d.block.heights.resize(n);
    d.block.mask.assign(n, 255);
    float lo = 0, hi = 0;
    for (size_t i = 0; i < n; ++i) {
      const float h = static_cast<float>(b.q[i] * b.step);
      d.block.heights[i] = h;
      lo = i == 0 ? h : std::min(lo, h);
      hi = i == 0 ? h : std::max(hi, h);
      if (!b.valid.empty() && !b.valid[i]) d.block.mask[i] = 0;
    }
    d.meta.min_h = lo;
    d.meta.max_h = hi;
    d.meta.vertex_error = std::move(b.vertex_error);
    if (analysis) {
      const tileformat::AnalysisBlock a = read_analysis(*analysis, id, block_size);
      d.block.analysis = analysis_texels(a);
      d.block.flow = flow_texels(a);
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
  loader_ = std::make_unique<Loader>(
      *package_.reader, decode_block(package_.block_size, package_.lattice, analysis_));
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
    if (!d.ok) {
      std::fprintf(stderr, "globe-view: warning: %s: tile %s: %s; drawing a coarser level there\n",
                   path_.c_str(), id.str().c_str(), d.error.c_str());
      e.state = BlockState::kBroken;
      free_slots_.push_back(slot);
      ++stats_.broken;
      continue;
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
