// Line tile cache (see line_cache.hpp).
#include "data/line_cache.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>

#include "tileformat/line_tile.hpp"

namespace globe::viewer {

using tileformat::TileId;

namespace {

constexpr size_t kMaxEmptyRecords = 8192;

uint32_t float_bits(double v) {
  return std::bit_cast<uint32_t>(static_cast<float>(v));
}

}  // namespace

DecodedLineTile line_tile_words(const tileformat::LineTile& t, const LineHighlight* highlight) {
  DecodedLineTile d;
  d.extent = t.extent;
  d.grid = t.grid;
  d.reach = t.reach;
  d.segments = t.segment_count();
  d.cell_entries = static_cast<uint32_t>(t.cell_segments.size());
  d.words.reserve(t.cell_offsets.size() + t.cell_segments.size() +
                  size_t{d.segments} * kLineWordsPerSegment);
  d.words.insert(d.words.end(), t.cell_offsets.begin(), t.cell_offsets.end());
  d.words.insert(d.words.end(), t.cell_segments.begin(), t.cell_segments.end());
  for (const tileformat::LineRun& r : t.runs) {
    const bool lit =
        highlight && std::binary_search(highlight->features.begin(), highlight->features.end(),
                                        t.feature_ids[r.feature]);
    const uint32_t class_id = lit ? highlight->class_id : r.class_id;
    double along = 0;
    for (uint32_t i = 0; i + 1 < r.vertex_count; ++i) {
      const tileformat::LineVertex a = t.vertices[r.first_vertex + i],
                                   b = t.vertices[r.first_vertex + i + 1];
      d.words.insert(d.words.end(), {float_bits(a.x), float_bits(a.y), float_bits(b.x),
                                     float_bits(b.y), class_id, float_bits(along)});
      const double length = std::hypot(double(b.x) - a.x, double(b.y) - a.y);
      d.longest = std::max(d.longest, static_cast<float>(length));
      along += length;
    }
  }
  return d;
}

std::optional<uint64_t> segment_feature(const tileformat::LineTile& t, uint32_t segment) {
  for (const tileformat::LineRun& r : t.runs) {
    if (segment + 1 < r.vertex_count) return t.feature_ids[r.feature];
    segment -= r.vertex_count - 1;
  }
  return std::nullopt;
}

LineCache::LineCache(const std::string& path, LinePackage package, uint64_t budget_bytes)
    : path_(path), package_(std::move(package)), arena_(budget_bytes / 4) {
  stats_.budget_bytes = budget_bytes;
  loader_ =
      std::make_unique<Loader>(*package_.reader, [this](TileId, std::span<const uint8_t> blob) {
        std::shared_ptr<const LineHighlight> h;
        {
          std::lock_guard lock(highlight_mutex_);
          h = highlight_;
        }
        return line_tile_words(tileformat::decode_line_tile(blob), h.get());
      });
}

void LineCache::set_highlight(LineHighlight highlight) {
  std::sort(highlight.features.begin(), highlight.features.end());
  {
    std::lock_guard lock(highlight_mutex_);
    highlight_ = highlight.features.empty()
                     ? nullptr
                     : std::make_shared<const LineHighlight>(std::move(highlight));
  }
  // Tiles decoded with the previous set are dropped, loaded or not.
  wait_for_loader();
  loader_->take_done();
  for (uint32_t r = 0; r < records_.size(); ++r)
    if (live_[r]) free_record(r);
  entries_.clear();
  wanted_.clear();
}

LineCache::~LineCache() = default;

uint32_t LineCache::new_record(TileId id) {
  uint32_t r;
  if (!free_records_.empty()) {
    r = free_records_.back();
    free_records_.pop_back();
  } else {
    r = static_cast<uint32_t>(records_.size());
    records_.emplace_back();
    live_.push_back(false);
  }
  records_[r] = LineRecord{};
  records_[r].id = id;
  live_[r] = true;
  return r;
}

void LineCache::free_record(uint32_t r) {
  const LineRecord& rec = records_[r];
  if (!rec.empty) arena_.release(rec.offset, rec.size);
  entries_.erase(rec.id);
  live_[r] = false;
  free_records_.push_back(r);
}

void LineCache::mark_used(uint32_t record) {
  if (!live(record)) return;
  auto it = entries_.find(records_[record].id);
  if (it != entries_.end()) it->second.last_used = frame_;
}

bool LineCache::request(TileId id) {
  // Pixels past the tiling's edge ask for tiles no package can have.
  if (id.z < package_.min_zoom || id.z > package_.max_zoom || !package_.tiling.contains(id))
    return false;
  auto [it, fresh] = entries_.try_emplace(id);
  it->second.last_used = frame_;
  if (!fresh) return false;  // loading, resident or known empty
  if (!package_.reader->has_tile(id)) {
    it->second.record = static_cast<int>(new_record(id));
    return true;
  }
  it->second.loading = true;
  wanted_.push_back({id, -1});
  return true;
}

void LineCache::flush_requests() {
  loader_->submit_coarsest_first(wanted_);
}

std::optional<uint64_t> LineCache::allocate_evicting(uint64_t words) {
  for (;;) {
    if (auto at = arena_.allocate(words)) return at;
    // Evict the least recently used tile that the last frame did not touch.
    int victim = -1;
    uint64_t victim_used = 0;
    for (uint32_t r = 0; r < records_.size(); ++r) {
      if (!live_[r] || records_[r].empty) continue;
      const uint64_t used = entries_.at(records_[r].id).last_used;
      if (used >= frame_) continue;
      if (victim < 0 || used < victim_used) victim = static_cast<int>(r), victim_used = used;
    }
    if (victim < 0) return std::nullopt;
    ++stats_.evictions;
    free_record(static_cast<uint32_t>(victim));
  }
}

std::vector<uint32_t> LineCache::take_loaded() {
  std::vector<uint32_t> out;
  for (Loader::Done& d : loader_->take_done()) {
    const TileId id = d.job.id;
    auto it = entries_.find(id);
    if (it == entries_.end()) continue;
    it->second.loading = false;
    stats_.bytes_read += d.bytes;
    if (!d.ok) {
      std::fprintf(stderr,
                   "globe-view: warning: %s: line tile %s: %s; the lines of its coarser or finer "
                   "tiles are drawn there\n",
                   path_.c_str(), id.str().c_str(), d.error.c_str());
      ++stats_.broken;
      const uint32_t r = new_record(id);
      records_[r].broken = true;
      it->second.record = static_cast<int>(r);
      continue;
    }
    const uint64_t size = std::max<size_t>(d.value.words.size(), 1);
    if (size > arena_.capacity()) {
      std::fprintf(stderr,
                   "globe-view: warning: %s: line tile %s needs %.1f MB, more than the line "
                   "budget (raise --cache-mb); its lines are not drawn\n",
                   path_.c_str(), id.str().c_str(), size * 4 / 1e6);
      ++stats_.broken;
      it->second.record = static_cast<int>(new_record(id));
      continue;
    }
    const auto offset = allocate_evicting(size);
    if (!offset) {
      entries_.erase(it);  // the budget is full of tiles in view; asked again later
      continue;
    }
    const uint32_t r = new_record(id);
    LineRecord& rec = records_[r];
    rec.empty = false;
    rec.size = size;
    rec.offset = *offset;
    rec.tile = std::move(d.value);
    it->second.record = static_cast<int>(r);
    it->second.last_used = frame_;
    ++stats_.loaded;
    out.push_back(r);
  }
  // Forget known-empty tiles nobody looked at lately (they are asked again).
  size_t empties = 0;
  for (uint32_t r = 0; r < records_.size(); ++r)
    empties += live_[r] && records_[r].empty;
  if (empties > kMaxEmptyRecords)
    for (uint32_t r = 0; r < records_.size(); ++r)
      if (live_[r] && records_[r].empty && entries_.at(records_[r].id).last_used + 1 < frame_)
        free_record(r);
  return out;
}

LineCacheStats LineCache::stats() const {
  LineCacheStats s = stats_;
  s.resident_bytes = arena_.used() * 4;
  for (uint32_t r = 0; r < records_.size(); ++r)
    if (live_[r]) (records_[r].empty ? s.known_empty : s.resident)++;
  return s;
}

}  // namespace globe::viewer
