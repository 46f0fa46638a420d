// Scratch storage (see staging_store.hpp).
#include "tileformat/staging_store.hpp"

#include <filesystem>

#include "tileformat/error.hpp"

namespace tileformat {

namespace {

void remove_store(const std::string& path) {
  std::error_code ec;
  std::filesystem::remove(path, ec);
  std::filesystem::remove(path + "-journal", ec);
}

}  // namespace

StagingStore::StagingStore(std::string path, int32_t key, Resume resume) : path_(std::move(path)) {
  std::error_code ec;
  if (resume == Resume::kContinue && std::filesystem::exists(path_, ec)) {
    // SQLite rolls a hot journal back on the first read.
    db_ = std::make_unique<SqliteDb>(path_, SqliteDb::Mode::kReadWriteCreate);
    try {
      if (db_->query_int("PRAGMA user_version").value_or(0) != key) db_.reset();
    } catch (const PackageError&) {
      db_.reset();  // unreadable: start over
    }
  }
  const bool fresh = !db_;
  if (fresh) {
    db_.reset();
    remove_store(path_);
    db_ = std::make_unique<SqliteDb>(path_, SqliteDb::Mode::kReadWriteCreate);
  }
  // Not fsynced: the journal is there for a killed process, not power loss.
  db_->exec(
      "PRAGMA journal_mode = TRUNCATE; PRAGMA synchronous = OFF; PRAGMA cache_size = -16384;");
  if (fresh) {
    db_->exec("PRAGMA user_version = " + std::to_string(key));
    db_->exec(
        "CREATE TABLE progress (seq INTEGER PRIMARY KEY, z INTEGER, pass INTEGER, done INTEGER, "
        "puts INTEGER)");
  }
  db_->exec("BEGIN");
}

StagingStore::~StagingStore() {
  tables_.clear();
  db_.reset();
  remove_store(path_);
}

namespace {

// One table per stage and zoom, keyed by (y, x) packed into the rowid (so
// rows are stored in list order, with no separate index): dropping a level
// is DROP TABLE, which frees its pages without journaling their content
// (DELETE copied every deleted page into the rollback journal).
std::string table_name(StageTag stage, int z) {
  return "s" + std::to_string(stage) + "_" + std::to_string(z);
}
int64_t row_key(TileId id) {
  return (static_cast<int64_t>(id.y) << 32) | id.x;
}

}  // namespace

StagingStore::Table& StagingStore::table(StageTag stage, int z) {
  const auto key = std::make_pair(stage, z);
  auto it = tables_.find(key);
  if (it != tables_.end()) return it->second;
  const std::string name = table_name(stage, z);
  db_->exec("CREATE TABLE IF NOT EXISTS " + name + " (key INTEGER PRIMARY KEY, data BLOB)");
  Table t;
  t.put =
      std::make_unique<SqliteStatement>(*db_, "INSERT OR REPLACE INTO " + name + " VALUES (?, ?)");
  t.get = std::make_unique<SqliteStatement>(*db_, "SELECT data FROM " + name + " WHERE key = ?");
  return tables_.emplace(key, std::move(t)).first->second;
}

namespace {

StageCheckpoint checkpoint_row(const SqliteStatement& st) {
  return StageCheckpoint{static_cast<int>(st.column_int(0)), static_cast<int>(st.column_int(1)),
                         static_cast<uint64_t>(st.column_int(2)),
                         static_cast<uint64_t>(st.column_int(3))};
}

}  // namespace

std::optional<StageCheckpoint> StagingStore::checkpoint() {
  SqliteStatement st(*db_, "SELECT z, pass, done, puts FROM progress ORDER BY seq DESC LIMIT 1");
  if (!st.step()) return std::nullopt;
  return checkpoint_row(st);
}

std::vector<StageCheckpoint> StagingStore::checkpoints(int z) {
  SqliteStatement st(*db_, "SELECT z, pass, done, puts FROM progress WHERE z = ? ORDER BY seq");
  st.bind(1, z);
  std::vector<StageCheckpoint> out;
  while (st.step())
    out.push_back(checkpoint_row(st));
  return out;
}

void StagingStore::put(StageTag stage, TileId id, const std::vector<uint8_t>& data) {
  Table& t = table(stage, id.z);
  t.put->bind(1, row_key(id)).bind(2, data);
  t.put->step();
  t.put->reset();
}

std::optional<std::vector<uint8_t>> StagingStore::get(StageTag stage, TileId id) {
  Table& t = table(stage, id.z);
  t.get->bind(1, row_key(id));
  std::optional<std::vector<uint8_t>> out;
  if (t.get->step()) {
    auto b = t.get->column_blob(0);
    out.emplace(b.begin(), b.end());
  }
  t.get->reset();
  return out;
}

std::vector<TileId> StagingStore::list(StageTag stage, int z) {
  table(stage, z);  // exists (empty) even if nothing was put
  SqliteStatement st(*db_, "SELECT key FROM " + table_name(stage, z) + " ORDER BY key");
  std::vector<TileId> out;
  while (st.step()) {
    const int64_t key = st.column_int(0);
    out.push_back({z, static_cast<uint32_t>(key & 0xffffffff), static_cast<uint32_t>(key >> 32)});
  }
  return out;
}

void StagingStore::drop(StageTag stage, int z) {
  tables_.erase({stage, z});
  db_->exec("DROP TABLE IF EXISTS " + table_name(stage, z));
}

void StagingStore::commit() {
  db_->exec("COMMIT; BEGIN");
  last_commit_ = std::chrono::steady_clock::now();
}

void StagingStore::commit_if_due(const StageCheckpoint& at) {
  if (std::chrono::steady_clock::now() - last_commit_ >= std::chrono::seconds(1)) commit(at);
}

void StagingStore::commit(const StageCheckpoint& at) {
  SqliteStatement st(*db_, "INSERT INTO progress (z, pass, done, puts) VALUES (?, ?, ?, ?)");
  st.bind(1, at.z).bind(2, at.pass).bind(3, static_cast<int64_t>(at.done));
  st.bind(4, static_cast<int64_t>(at.puts));
  st.step();
  commit();
}

}  // namespace tileformat
