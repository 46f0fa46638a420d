// Recently cut tiles (see tile_cache.hpp).
#include "tile_cache.hpp"

namespace globe::serve {

std::shared_ptr<const std::string> TileCache::get(const std::string& key) {
  std::lock_guard lock(mutex_);
  const auto it = index_.find(key);
  if (it == index_.end()) return nullptr;
  order_.splice(order_.begin(), order_, it->second);
  return it->second->second;
}

void TileCache::put(const std::string& key, std::shared_ptr<const std::string> bytes) {
  if (!bytes || bytes->size() > max_bytes_) return;
  std::lock_guard lock(mutex_);
  if (index_.count(key)) return;
  bytes_ += bytes->size();
  order_.emplace_front(key, std::move(bytes));
  index_[key] = order_.begin();
  while (bytes_ > max_bytes_ && !order_.empty()) {
    bytes_ -= order_.back().second->size();
    index_.erase(order_.back().first);
    order_.pop_back();
  }
}

size_t TileCache::bytes() const {
  std::lock_guard lock(mutex_);
  return bytes_;
}

}  // namespace globe::serve
