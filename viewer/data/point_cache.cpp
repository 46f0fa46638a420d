// Point tile cache (see point_cache.hpp).
#include "data/point_cache.hpp"

#include <cstdio>

namespace globe::viewer {

using tileformat::TileId;

namespace {

uint64_t tile_bytes(const tileformat::PointTile& t) {
  return sizeof(t) + t.places.size() * sizeof(tileformat::Place) + t.values.size() * sizeof(float) +
         (t.cell_offsets.size() + t.cell_places.size()) * sizeof(uint32_t);
}

}  // namespace

PointCache::PointCache(PointPackage package, uint64_t budget_bytes) : package_(std::move(package)) {
  stats_.budget_bytes = budget_bytes;
  loader_ = std::make_unique<Loader>(*package_.reader, [](TileId, std::span<const uint8_t> blob) {
    return tileformat::decode_point_tile(blob);
  });
}

PointCache::~PointCache() = default;

bool PointCache::exists(TileId id) {
  const tileformat::CommonMetadata& c = package_.meta.common;
  if (id.z < c.min_zoom || id.z > c.max_zoom || !c.tiling.contains(id)) return false;
  auto [it, fresh] = exists_.try_emplace(id, false);
  if (fresh) it->second = package_.reader->has_tile(id);
  return it->second;
}

const tileformat::PointTile* PointCache::get(TileId id) {
  auto it = entries_.find(id);
  if (it == entries_.end()) {
    if (!exists(id)) return nullptr;
    entries_.emplace(id, Entry{});
    wanted_.push_back({id, -1});
    ++stats_.loading;
    return nullptr;
  }
  it->second.last_used = frame_;
  return it->second.state == State::kResident ? it->second.tile.get() : nullptr;
}

bool PointCache::loading(TileId id) const {
  auto it = entries_.find(id);
  return it != entries_.end() && it->second.state == State::kLoading;
}

bool PointCache::broken(TileId id) const {
  auto it = entries_.find(id);
  return it != entries_.end() && it->second.state == State::kBroken;
}

void PointCache::flush_requests() {
  loader_->submit_coarsest_first(wanted_);
}

void PointCache::evict_for(uint64_t bytes) {
  while (stats_.resident_bytes + bytes > stats_.budget_bytes) {
    auto victim = entries_.end();
    for (auto it = entries_.begin(); it != entries_.end(); ++it)
      if (it->second.state == State::kResident && it->second.last_used < frame_ &&
          (victim == entries_.end() || it->second.last_used < victim->second.last_used ||
           (it->second.last_used == victim->second.last_used && it->first < victim->first)))
        victim = it;
    if (victim == entries_.end()) return;  // everything resident is in use: go over
    stats_.resident_bytes -= victim->second.bytes;
    --stats_.resident;
    ++stats_.evictions;
    entries_.erase(victim);
  }
}

size_t PointCache::take_loaded() {
  std::vector<Loader::Done> done = loader_->take_done();
  for (Loader::Done& d : done) {
    --stats_.loading;
    stats_.bytes_read += d.bytes;
    auto it = entries_.find(d.job.id);
    if (it == entries_.end()) continue;
    if (d.absent) {
      it->second.state = State::kAbsent;
      continue;
    }
    if (!d.ok) {
      ++stats_.broken;
      std::fprintf(stderr,
                   "globe-view: warning: %s: point tile %s: %s; the charts of its finer or "
                   "coarser tiles are drawn there\n",
                   package_.reader->path().c_str(), d.job.id.str().c_str(), d.error.c_str());
      it->second.state = State::kBroken;
      continue;
    }
    const uint64_t bytes = tile_bytes(d.value);
    evict_for(bytes);
    it = entries_.find(d.job.id);  // eviction may rehash
    it->second.tile = std::make_shared<const tileformat::PointTile>(std::move(d.value));
    it->second.bytes = bytes;
    it->second.state = State::kResident;
    stats_.resident_bytes += bytes;
    ++stats_.resident;
    ++stats_.loaded;
  }
  return done.size();
}

PointCacheStats PointCache::stats() const {
  return stats_;
}

}  // namespace globe::viewer
