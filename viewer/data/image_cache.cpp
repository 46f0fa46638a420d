// Image tiles on their way to the GPU (see image_cache.hpp).
#include "data/image_cache.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "runtime/rgba_decode.hpp"

namespace globe::viewer {

using tileformat::TileId;

namespace {

constexpr size_t kMaxAbsent = 1 << 16;  // known-absent tiles kept before forgetting idle ones

}  // namespace

ImageMips decode_image_mips(std::span<const uint8_t> blob, int size) {
  RgbaImage img = decode_rgba(blob);
  if (img.width != size || img.height != size)
    throw std::runtime_error("a " + std::to_string(img.width) + " x " + std::to_string(img.height) +
                             " image in a package of " + std::to_string(size) + " px tiles");
  // Premultiplied alpha, so that filtering and mips never bleed the colour
  // of transparent pixels.
  std::vector<uint8_t>& px = img.rgba;
  for (size_t i = 0; i < px.size(); i += 4) {
    const unsigned a = px[i + 3];
    for (int c = 0; c < 3; ++c)
      px[i + c] = static_cast<uint8_t>((px[i + c] * a + 127) / 255);
  }
  ImageMips m;
  m.levels.push_back(std::move(px));
  for (int s = size / 2; s >= 1; s /= 2) {
    const std::vector<uint8_t>& fine = m.levels.back();
    const int fs = s * 2;
    std::vector<uint8_t> coarse(size_t(s) * s * 4);
    for (int y = 0; y < s; ++y)
      for (int x = 0; x < s; ++x)
        for (int c = 0; c < 4; ++c) {
          auto at = [&](int xx, int yy) { return unsigned(fine[(size_t(yy) * fs + xx) * 4 + c]); };
          coarse[(size_t(y) * s + x) * 4 + c] =
              static_cast<uint8_t>((at(2 * x, 2 * y) + at(2 * x + 1, 2 * y) + at(2 * x, 2 * y + 1) +
                                    at(2 * x + 1, 2 * y + 1) + 2) /
                                   4);
        }
    m.levels.push_back(std::move(coarse));
  }
  return m;
}

ImageCache::ImageCache(const std::string& path, ImagePackage package, int slots)
    : path_(path),
      package_(std::move(package)),
      slots_(std::max(slots, 1)),
      slot_tile_(size_t(slots_), TileId{-1, 0, 0}),
      slot_used_(size_t(slots_), 0) {
  stats_.slots = size_t(slots_);
  const int size = package_.tile_size;
  loader_ = std::make_unique<Loader>(*package_.reader, [size](TileId, std::span<const uint8_t> b) {
    return decode_image_mips(b, size);
  });
}

ImageCache::~ImageCache() = default;

int ImageCache::levels() const {
  int n = 1;
  for (int s = package_.tile_size; s > 1; s /= 2)
    ++n;
  return n;
}

void ImageCache::mark_used(uint32_t slot) {
  if (slot >= slot_used_.size() || slot_tile_[slot].z < 0) return;
  slot_used_[slot] = frame_;
  auto it = entries_.find(slot_tile_[slot]);
  if (it != entries_.end()) it->second.last_used = frame_;
}

bool ImageCache::request(TileId id) {
  // Pixels past the tiling's edge ask for tiles no package can have.
  if (id.z < package_.min_zoom || id.z > package_.max_zoom || !package_.tiling.contains(id))
    return false;
  auto [it, fresh] = entries_.try_emplace(id);
  it->second.last_used = frame_;
  if (!fresh) return false;  // loading, resident or known
  if (!package_.reader->has_tile(id)) {
    it->second.value = kImageAbsent;
    return true;
  }
  it->second.loading = true;
  wanted_.push_back({id, -1});
  return true;
}

void ImageCache::flush_requests() {
  loader_->submit_coarsest_first(wanted_);
}

int ImageCache::take_slot() {
  int victim = -1;
  for (int s = 0; s < slots_; ++s) {
    if (slot_tile_[s].z < 0) return s;
    if (slot_used_[s] >= frame_) continue;  // read by the last frame
    if (victim < 0 || slot_used_[s] < slot_used_[victim]) victim = s;
  }
  if (victim >= 0) {
    entries_.erase(slot_tile_[victim]);
    slot_tile_[victim] = TileId{-1, 0, 0};
    ++stats_.evictions;
  }
  return victim;
}

std::vector<std::pair<uint32_t, ImageMips>> ImageCache::take_loaded() {
  std::vector<std::pair<uint32_t, ImageMips>> out;
  for (Loader::Done& d : loader_->take_done()) {
    const TileId id = d.job.id;
    auto it = entries_.find(id);
    if (it == entries_.end()) continue;
    it->second.loading = false;
    stats_.bytes_read += d.bytes;
    if (d.absent) {
      it->second.value = kImageAbsent;
      continue;
    }
    if (!d.ok) {
      std::fprintf(stderr,
                   "globe-view: warning: %s: image tile %s: %s; the image of its finer or coarser "
                   "tiles is shown there\n",
                   path_.c_str(), id.str().c_str(), d.error.c_str());
      ++stats_.broken;
      it->second.value = kImageBroken;
      continue;
    }
    const int slot = take_slot();
    if (slot < 0) {
      entries_.erase(it);  // every slot is in view; asked again later
      continue;
    }
    slot_tile_[slot] = id;
    slot_used_[slot] = frame_;
    it->second.value = static_cast<uint32_t>(slot);
    it->second.last_used = frame_;
    ++stats_.loaded;
    out.emplace_back(static_cast<uint32_t>(slot), std::move(d.value));
  }
  // Forget known-absent tiles nobody looked at lately (they are asked again).
  size_t absent = 0;
  for (const auto& [id, e] : entries_)
    absent += !e.loading && e.value == kImageAbsent;
  if (absent > kMaxAbsent)
    std::erase_if(entries_, [&](const auto& kv) {
      return !kv.second.loading && kv.second.value == kImageAbsent &&
             kv.second.last_used + 1 < frame_;
    });
  return out;
}

std::vector<std::pair<TileId, uint32_t>> ImageCache::table() const {
  std::vector<std::pair<TileId, uint32_t>> t;
  for (const auto& [id, e] : entries_)
    if (!e.loading) t.emplace_back(id, e.value);
  // A fixed order, so the GPU table (and so the image) never depends on
  // the hash map's iteration order.
  std::sort(t.begin(), t.end());
  return t;
}

ImageCacheStats ImageCache::stats() const {
  ImageCacheStats s = stats_;
  for (const auto& [id, e] : entries_) {
    s.loading += e.loading;
    if (e.loading) continue;
    if (e.value == kImageAbsent) ++s.known_absent;
    if (e.value < kImageBroken) ++s.resident;
  }
  return s;
}

}  // namespace globe::viewer
