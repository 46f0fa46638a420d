// DiskCache (net/disk_cache.hpp): the only file of lib/net that calls
// SQLite. One table, entries, with an index on (last_used, size) that
// answers both the total (SUM(size), summed from the index alone: the
// bodies are never read for it) and the eviction order. last_used is a use
// counter (MAX + 1 in the writing transaction), not a time: uses within one
// second keep their order, and two processes sharing the file draw from one
// sequence. Every write is a BEGIN IMMEDIATE transaction; the total is
// recounted in it, so another process's writes are never missed. The file
// shrinks through auto_vacuum=INCREMENTAL, set before the first table.
// Rollback journal, never WAL (a WAL file grows while a reader holds it).
#include "net/disk_cache.hpp"

#include <sqlite3.h>

#include <filesystem>
#include <mutex>

#include "net/http_client.hpp"

namespace globe::net {
namespace {

constexpr int kBusyTimeoutMs = 5000;

// The connection and what every query needs of it.
struct Connection {
  std::string path;
  uint64_t max_bytes = 0;
  sqlite3* db = nullptr;
  mutable std::mutex mu;  // one connection, used by one thread at a time

  [[noreturn]] void fail(const std::string& what) const {
    throw NetError(path + ": " + what + ": " + (db ? sqlite3_errmsg(db) : "not open") +
                   "; delete the file to start an empty cache");
  }

  void exec(const char* sql) {
    char* message = nullptr;
    if (sqlite3_exec(db, sql, nullptr, nullptr, &message) != SQLITE_OK) {
      const std::string why = message ? message : sqlite3_errmsg(db);
      sqlite3_free(message);
      throw NetError(path + ": cache database: " + why +
                     "; delete the file to start an empty cache");
    }
  }

  void evict_to_fit();
};

// A prepared statement, finalized when it goes (which also ends its read:
// no statement outlives its call and keeps the other connection waiting).
class Statement {
 public:
  Statement(const Connection& cache, sqlite3* db, const char* sql) : cache_(cache) {
    if (sqlite3_prepare_v2(db, sql, -1, &stmt_, nullptr) != SQLITE_OK)
      cache_.fail("cannot prepare a query");
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  void bind(int i, const std::string& text) {
    check(
        sqlite3_bind_text(stmt_, i, text.data(), static_cast<int>(text.size()), SQLITE_TRANSIENT));
  }
  void bind(int i, const std::vector<uint8_t>& blob) {
    // A zero-length blob, not NULL: an empty body is a body.
    check(blob.empty() ? sqlite3_bind_zeroblob(stmt_, i, 0)
                       : sqlite3_bind_blob64(stmt_, i, blob.data(), blob.size(), SQLITE_TRANSIENT));
  }
  void bind(int i, int64_t v) { check(sqlite3_bind_int64(stmt_, i, v)); }

  // True while there is a row.
  bool step() {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    cache_.fail("cannot read or write the cache");
  }
  void reset() { sqlite3_reset(stmt_); }
  int64_t integer(int col) const { return sqlite3_column_int64(stmt_, col); }
  std::string text(int col) const {
    const auto* p = sqlite3_column_text(stmt_, col);
    return p ? std::string(reinterpret_cast<const char*>(p),
                           static_cast<size_t>(sqlite3_column_bytes(stmt_, col)))
             : std::string();
  }
  std::vector<uint8_t> blob(int col) const {
    const auto* p = static_cast<const uint8_t*>(sqlite3_column_blob(stmt_, col));
    const int n = sqlite3_column_bytes(stmt_, col);
    return p ? std::vector<uint8_t>(p, p + n) : std::vector<uint8_t>();
  }

 private:
  void check(int rc) {
    if (rc != SQLITE_OK) cache_.fail("cannot bind a value");
  }
  const Connection& cache_;
  sqlite3_stmt* stmt_ = nullptr;
};

// BEGIN IMMEDIATE ... COMMIT; rolled back if left without commit().
class Transaction {
 public:
  explicit Transaction(Connection& cache) : cache_(cache) { cache_.exec("BEGIN IMMEDIATE"); }
  ~Transaction() {
    if (!done_) sqlite3_exec(cache_.db, "ROLLBACK", nullptr, nullptr, nullptr);
  }
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  void commit() {
    cache_.exec("COMMIT");
    done_ = true;
  }

 private:
  Connection& cache_;
  bool done_ = false;
};

constexpr const char* kNextUse = "(SELECT COALESCE(MAX(last_used), 0) + 1 FROM entries)";

// Deletes the least recently used entries until the bodies fit, then gives
// the freed pages back to the file system. Inside a transaction.
void Connection::evict_to_fit() {
  int64_t total = 0;
  {
    Statement sum(*this, db, "SELECT COALESCE(SUM(size), 0) FROM entries");
    if (sum.step()) total = sum.integer(0);
  }
  if (static_cast<uint64_t>(total) <= max_bytes) return;
  std::vector<std::string> victims;
  {
    Statement oldest(*this, db, "SELECT key, size FROM entries ORDER BY last_used");
    while (static_cast<uint64_t>(total) > max_bytes && oldest.step()) {
      victims.push_back(oldest.text(0));
      total -= oldest.integer(1);
    }
  }
  Statement erase(*this, db, "DELETE FROM entries WHERE key = ?1");
  for (const std::string& key : victims) {
    erase.bind(1, key);
    erase.step();
    erase.reset();
  }
  exec("PRAGMA incremental_vacuum");
}

}  // namespace

struct DiskCache::Impl : Connection {};

DiskCache::DiskCache(const std::string& folder, uint64_t max_bytes)
    : impl_(std::make_unique<Impl>()) {
  Impl& c = *impl_;
  c.path = (std::filesystem::path(folder) / "http-cache.sqlite").string();
  c.max_bytes = max_bytes;
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec)
    throw NetError(c.path + ": cannot create the cache folder " + folder + ": " + ec.message());
  const int rc =
      sqlite3_open_v2(c.path.c_str(), &c.db,
                      SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_NOMUTEX, nullptr);
  if (rc != SQLITE_OK) {
    const std::string why = c.db ? sqlite3_errmsg(c.db) : sqlite3_errstr(rc);
    sqlite3_close(c.db);
    c.db = nullptr;
    throw NetError(c.path + ": cannot open the cache: " + why);
  }
  try {
    sqlite3_extended_result_codes(c.db, 1);
    if (sqlite3_busy_timeout(c.db, kBusyTimeoutMs) != SQLITE_OK)
      c.fail("cannot set a busy timeout");
    // auto_vacuum first: it only takes on a file without tables.
    c.exec("PRAGMA auto_vacuum = INCREMENTAL");
    c.exec("PRAGMA journal_mode = DELETE");
    // No fsync at commit: a crash of the process still rolls back from the
    // journal; only a crash of the machine can damage the file, which holds
    // nothing that cannot be downloaded again. With fsync each commit took
    // 14 ms here (a find marks its entry used: a commit per cache hit),
    // without 0.1 ms.
    c.exec("PRAGMA synchronous = OFF");
    {
      Transaction t(c);
      c.exec(
          "CREATE TABLE IF NOT EXISTS entries(key TEXT PRIMARY KEY, body BLOB, content_type TEXT, "
          "etag TEXT, last_modified TEXT, stored_at INTEGER, expires_at INTEGER, "
          "last_used INTEGER, size INTEGER)");
      c.exec("CREATE INDEX IF NOT EXISTS entries_last_used ON entries(last_used, size)");
      t.commit();
    }
    {
      // A file made without incremental vacuum (by hand, by an old
      // version) is converted once.
      Statement mode(c, c.db, "PRAGMA auto_vacuum");
      const bool incremental = mode.step() && mode.integer(0) == 2;
      if (!incremental) c.exec("VACUUM");
    }
    // A smaller cap than the file was filled with takes effect now.
    Transaction t(c);
    c.evict_to_fit();
    t.commit();
  } catch (...) {
    sqlite3_close_v2(c.db);
    c.db = nullptr;
    throw;
  }
}

DiskCache::~DiskCache() {
  if (impl_ && impl_->db) sqlite3_close_v2(impl_->db);
}

std::optional<CacheEntry> DiskCache::find(const std::string& key) {
  Impl& c = *impl_;
  std::lock_guard lock(c.mu);
  Transaction t(c);
  std::optional<CacheEntry> out;
  {
    Statement q(c, c.db,
                "SELECT body, content_type, etag, last_modified, stored_at, expires_at "
                "FROM entries WHERE key = ?1");
    q.bind(1, key);
    if (q.step()) {
      CacheEntry e;
      e.body = q.blob(0);
      e.content_type = q.text(1);
      e.etag = q.text(2);
      e.last_modified = q.text(3);
      e.stored_at = q.integer(4);
      e.expires_at = q.integer(5);
      out = std::move(e);
    }
  }
  if (out) {
    Statement use(
        c, c.db,
        (std::string("UPDATE entries SET last_used = ") + kNextUse + " WHERE key = ?1").c_str());
    use.bind(1, key);
    use.step();
  }
  t.commit();
  return out;
}

void DiskCache::put(const std::string& key, const CacheEntry& entry) {
  Impl& c = *impl_;
  std::lock_guard lock(c.mu);
  Transaction t(c);
  if (entry.body.size() > c.max_bytes) {
    // Larger than the whole cache: not kept, and no older answer either.
    Statement erase(c, c.db, "DELETE FROM entries WHERE key = ?1");
    erase.bind(1, key);
    erase.step();
  } else {
    Statement q(c, c.db,
                (std::string("INSERT OR REPLACE INTO entries(key, body, content_type, etag, "
                             "last_modified, stored_at, expires_at, last_used, size) "
                             "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ") +
                 kNextUse + ", ?8)")
                    .c_str());
    q.bind(1, key);
    q.bind(2, entry.body);
    q.bind(3, entry.content_type);
    q.bind(4, entry.etag);
    q.bind(5, entry.last_modified);
    q.bind(6, entry.stored_at);
    q.bind(7, entry.expires_at);
    q.bind(8, static_cast<int64_t>(entry.body.size()));
    q.step();
  }
  c.evict_to_fit();
  t.commit();
}

void DiskCache::refresh(const std::string& key, int64_t expires_at, const std::string& etag,
                        const std::string& last_modified) {
  Impl& c = *impl_;
  std::lock_guard lock(c.mu);
  Transaction t(c);
  Statement q(c, c.db,
              (std::string("UPDATE entries SET expires_at = ?2, "
                           "etag = COALESCE(NULLIF(?3, ''), etag), "
                           "last_modified = COALESCE(NULLIF(?4, ''), last_modified), "
                           "last_used = ") +
               kNextUse + " WHERE key = ?1")
                  .c_str());
  q.bind(1, key);
  q.bind(2, expires_at);
  q.bind(3, etag);
  q.bind(4, last_modified);
  q.step();
  t.commit();
}

void DiskCache::erase(const std::string& key) {
  Impl& c = *impl_;
  std::lock_guard lock(c.mu);
  Transaction t(c);
  {
    Statement q(c, c.db, "DELETE FROM entries WHERE key = ?1");
    q.bind(1, key);
    q.step();
  }
  c.exec("PRAGMA incremental_vacuum");
  t.commit();
}

uint64_t DiskCache::body_bytes() const {
  const Impl& c = *impl_;
  std::lock_guard lock(c.mu);
  Statement q(c, c.db, "SELECT COALESCE(SUM(size), 0) FROM entries");
  return q.step() ? static_cast<uint64_t>(q.integer(0)) : 0;
}

uint64_t DiskCache::entries() const {
  const Impl& c = *impl_;
  std::lock_guard lock(c.mu);
  Statement q(c, c.db, "SELECT COUNT(*) FROM entries");
  return q.step() ? static_cast<uint64_t>(q.integer(0)) : 0;
}

const std::string& DiskCache::path() const {
  return impl_->path;
}

}  // namespace globe::net
