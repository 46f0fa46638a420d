// DiskCache: HTTP answers kept between runs, one SQLite file per cache folder
// (FOLDER/http-cache.sqlite), bounded in bytes with least-recently-used
// eviction that really shrinks the file (incremental vacuum), safe with two
// processes using the same folder at once (SQLite locking with a busy
// timeout; no WAL that could grow without bound). Used by HttpClient; usable
// alone (tests, a cache-inspecting command). SQLite is called from
// src/disk_cache.cpp only.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace globe::net {

struct CacheEntry {
  std::vector<uint8_t> body;
  std::string content_type;
  std::string etag;           // "" if none
  std::string last_modified;  // as sent, "" if none
  int64_t stored_at = 0;      // Unix seconds
  int64_t expires_at = 0;     // Unix seconds when it goes stale (0: stale at once)
};

class DiskCache {
 public:
  // Opens or creates FOLDER/http-cache.sqlite (the folder too). Throws
  // NetError naming the file when it cannot.
  DiskCache(const std::string& folder, uint64_t max_bytes);
  ~DiskCache();
  DiskCache(const DiskCache&) = delete;
  DiskCache& operator=(const DiskCache&) = delete;

  // `key`: the URL, plus "#range=A-B" for a range request. Marks it used.
  std::optional<CacheEntry> find(const std::string& key);
  // Stores or replaces; evicts least recently used entries until the bodies
  // fit max_bytes, and gives the freed pages back to the file system.
  void put(const std::string& key, const CacheEntry& entry);
  // After a 304: a new expiry (and validators, if the 304 sent new ones).
  // An empty etag or last_modified keeps the stored one. No effect on a key
  // that is not stored (evicted meanwhile).
  void refresh(const std::string& key, int64_t expires_at, const std::string& etag,
               const std::string& last_modified);
  void erase(const std::string& key);

  uint64_t body_bytes() const;  // the stored bodies' total
  uint64_t entries() const;
  const std::string& path() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace globe::net
