// FillOnceCache: values made on demand by the first thread that asks for
// them — the others wait for that one, nobody makes a value twice — and kept
// in a least-recently-used list of a given length (a value still in use
// lives on in its users). Shared by the remote elevation sources: decoded
// source tiles (raster_dem_reader), sampled meshes (quantized_mesh_reader),
// quantized grids with their node errors (block_synthesizer).
#pragma once

#include <cstddef>
#include <list>
#include <map>
#include <memory>
#include <mutex>

namespace globe::viewer {

template <class Key, class Value>
class FillOnceCache {
 public:
  explicit FillOnceCache(size_t capacity) : capacity_(capacity) {}

  // The value of `key`, made by `make()` if nobody has; a throw from make()
  // passes through and leaves it unmade (tried again on the next ask).
  template <class Make>
  std::shared_ptr<const Value> get(const Key& key, Make make) {
    std::shared_ptr<Slot> slot;
    {
      std::lock_guard lock(mutex_);
      auto it = slots_.find(key);
      if (it != slots_.end()) {
        lru_.splice(lru_.begin(), lru_, it->second.at);
        slot = it->second.slot;
      } else {
        lru_.push_front(key);
        slot = std::make_shared<Slot>();
        slots_.emplace(key, Entry{slot, lru_.begin()});
        while (slots_.size() > capacity_) {
          slots_.erase(lru_.back());
          lru_.pop_back();
        }
      }
    }
    std::lock_guard fill(slot->fill);
    if (!slot->value) slot->value = make();
    return slot->value;
  }
  // Whether `key` is made or being made now.
  bool contains(const Key& key) {
    std::lock_guard lock(mutex_);
    return slots_.count(key) != 0;
  }

 private:
  struct Slot {
    std::mutex fill;
    std::shared_ptr<const Value> value;  // null until made
  };
  struct Entry {
    std::shared_ptr<Slot> slot;
    typename std::list<Key>::iterator at;
  };
  size_t capacity_;
  std::mutex mutex_;    // guards lru_ and slots_
  std::list<Key> lru_;  // most recent first
  std::map<Key, Entry> slots_;
};

}  // namespace globe::viewer
