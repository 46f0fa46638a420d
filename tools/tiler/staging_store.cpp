// Scratch storage (see staging_store.hpp).
#include "staging_store.hpp"

#include <filesystem>

#include "tileformat/error.hpp"

namespace globe {

using tileformat::SqliteDb;
using tileformat::SqliteStatement;

namespace {

void remove_store(const std::string& path) {
  std::error_code ec;
  std::filesystem::remove(path, ec);
  std::filesystem::remove(path + "-journal", ec);
}

}  // namespace

StagingStore::StagingStore(std::string path, int32_t key, bool resume) : path_(std::move(path)) {
  std::error_code ec;
  if (resume && std::filesystem::exists(path_, ec)) {
    // SQLite rolls a hot journal back on the first read.
    db_ = std::make_unique<SqliteDb>(path_, SqliteDb::Mode::kReadWriteCreate);
    try {
      if (db_->query_int("PRAGMA user_version").value_or(0) != key) db_.reset();
    } catch (const tileformat::PackageError&) {
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
        "CREATE TABLE stage (kind INTEGER, z INTEGER, x INTEGER, y INTEGER, data BLOB, PRIMARY "
        "KEY (kind, z, y, x));"
        "CREATE TABLE progress (seq INTEGER PRIMARY KEY, z INTEGER, pass INTEGER, done INTEGER, "
        "puts INTEGER)");
  }
  put_ = std::make_unique<SqliteStatement>(*db_,
                                           "INSERT OR REPLACE INTO stage VALUES (?, ?, ?, ?, ?)");
  get_ = std::make_unique<SqliteStatement>(
      *db_, "SELECT data FROM stage WHERE kind = ? AND z = ? AND x = ? AND y = ?");
  db_->exec("BEGIN");
}

StagingStore::~StagingStore() {
  put_.reset();
  get_.reset();
  db_.reset();
  remove_store(path_);
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

void StagingStore::put(Stage stage, tileformat::TileId id, const std::vector<uint8_t>& data) {
  put_->bind(1, static_cast<int>(stage)).bind(2, id.z).bind(3, id.x).bind(4, id.y).bind(5, data);
  put_->step();
  put_->reset();
}

std::optional<std::vector<uint8_t>> StagingStore::get(Stage stage, tileformat::TileId id) {
  get_->bind(1, static_cast<int>(stage)).bind(2, id.z).bind(3, id.x).bind(4, id.y);
  std::optional<std::vector<uint8_t>> out;
  if (get_->step()) {
    auto b = get_->column_blob(0);
    out.emplace(b.begin(), b.end());
  }
  get_->reset();
  return out;
}

std::vector<tileformat::TileId> StagingStore::list(Stage stage, int z) {
  SqliteStatement st(*db_, "SELECT x, y FROM stage WHERE kind = ? AND z = ? ORDER BY y, x");
  st.bind(1, static_cast<int>(stage)).bind(2, z);
  std::vector<tileformat::TileId> out;
  while (st.step())
    out.push_back(
        {z, static_cast<uint32_t>(st.column_int(0)), static_cast<uint32_t>(st.column_int(1))});
  return out;
}

void StagingStore::drop(Stage stage, int z) {
  SqliteStatement st(*db_, "DELETE FROM stage WHERE kind = ? AND z = ?");
  st.bind(1, static_cast<int>(stage)).bind(2, z);
  st.step();
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

std::vector<uint8_t> pack_u32(const std::vector<uint32_t>& v) {
  std::vector<uint8_t> out(v.size() * 4);
  for (size_t i = 0; i < v.size(); ++i)
    for (int b = 0; b < 4; ++b)
      out[4 * i + b] = static_cast<uint8_t>(v[i] >> (8 * b));
  return out;
}

std::vector<uint32_t> unpack_u32(const std::vector<uint8_t>& bytes) {
  std::vector<uint32_t> out(bytes.size() / 4);
  for (size_t i = 0; i < out.size(); ++i)
    for (int b = 0; b < 4; ++b)
      out[i] |= uint32_t{bytes[4 * i + b]} << (8 * b);
  return out;
}

}  // namespace globe
