// A thread-safe cache of immutable values up to a byte budget, the least
// recently used dropped first: the decoded blocks, triangle errors and cut
// tiles that the server's request threads (and an export's workers) share,
// so that each is made once whatever thread asks, and memory stays under the
// budget whatever the load. A value is held by shared_ptr: one dropped from
// the cache lives on while a thread still uses it. A null value is a valid
// entry ("known absent", e.g. a tile the package lacks).
//
// Two threads missing the same key at once both make the value; the second
// put keeps the first. Values are pure functions of their keys here, so that
// costs time, never correctness.
#pragma once

#include <cstddef>
#include <list>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <utility>

namespace globe::web {

template <typename Key, typename Value>
class LruCache {
 public:
  explicit LruCache(size_t max_bytes) : max_bytes_(max_bytes) {}

  // Whether the key is cached; its value (perhaps null) in `out`.
  bool get(const Key& key, std::shared_ptr<const Value>& out) {
    std::lock_guard lock(mutex_);
    const auto it = index_.find(key);
    if (it == index_.end()) return false;
    order_.splice(order_.begin(), order_, it->second);
    out = it->second->value;
    return true;
  }
  std::shared_ptr<const Value> get(const Key& key) {
    std::shared_ptr<const Value> out;
    get(key, out);
    return out;
  }

  // Keeps `value` under `key` costing `bytes` (a value larger than the whole
  // budget is not kept); an existing entry stays.
  void put(const Key& key, std::shared_ptr<const Value> value, size_t bytes) {
    if (bytes > max_bytes_) return;
    std::lock_guard lock(mutex_);
    if (index_.count(key)) return;
    bytes_ += bytes;
    order_.push_front(Entry{key, std::move(value), bytes});
    index_[key] = order_.begin();
    while (bytes_ > max_bytes_ && !order_.empty()) {
      bytes_ -= order_.back().bytes;
      index_.erase(order_.back().key);
      order_.pop_back();
    }
  }

  size_t bytes() const {
    std::lock_guard lock(mutex_);
    return bytes_;
  }
  size_t max_bytes() const { return max_bytes_; }

 private:
  struct Entry {
    Key key;
    std::shared_ptr<const Value> value;
    size_t bytes;
  };
  mutable std::mutex mutex_;
  size_t max_bytes_, bytes_ = 0;
  std::list<Entry> order_;  // most recent first
  std::unordered_map<Key, typename std::list<Entry>::iterator> index_;
};

}  // namespace globe::web
