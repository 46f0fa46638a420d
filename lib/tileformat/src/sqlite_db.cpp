// SQLite wrapper: checked calls, errors with the file name and SQLite's
// words (the SQL itself only with GLOBE_DEBUG_SQL=1: users see no SQL).
#include "tileformat/sqlite_db.hpp"

#include <sqlite3.h>

#include <cstdlib>

#include "tileformat/error.hpp"

namespace tileformat {
namespace {

// " [SQL: ...]" for developers who ask for it, else nothing.
std::string sql_for_debugging(const std::string& sql) {
  const char* debug = std::getenv("GLOBE_DEBUG_SQL");
  if (sql.empty() || !debug || std::string(debug) != "1") return "";
  return " [SQL: " + sql.substr(0, 200) + "]";
}

}  // namespace

SqliteDb::SqliteDb(const std::string& path, Mode mode) : path_(path) {
  // Readers are serialized (one mutex per connection) so that the viewer's
  // threads can share one connection, and with it one open file: a package
  // replaced on disk while it is open is never half seen. Writers belong to
  // one thread.
  const int flags = mode == Mode::kReadOnly
                        ? SQLITE_OPEN_READONLY | SQLITE_OPEN_FULLMUTEX
                        : SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_NOMUTEX;
  int rc = sqlite3_open_v2(path.c_str(), &db_, flags, nullptr);
  if (rc != SQLITE_OK) {
    std::string msg = db_ ? sqlite3_errmsg(db_) : sqlite3_errstr(rc);
    sqlite3_close(db_);
    db_ = nullptr;
    throw PackageError(path + ": cannot open database: " + msg);
  }
  sqlite3_extended_result_codes(db_, 1);
}

SqliteDb::~SqliteDb() {
  if (db_) sqlite3_close_v2(db_);
}

void SqliteDb::close() {
  if (!db_) return;
  int rc = sqlite3_close(db_);
  if (rc != SQLITE_OK) fail("close", "");
  db_ = nullptr;
}

int64_t SqliteDb::last_insert_rowid() const {
  return sqlite3_last_insert_rowid(db_);
}

void SqliteDb::fail(const std::string& what, const std::string& sql) const {
  const std::string reason = db_ ? sqlite3_errmsg(db_) : "closed";
  throw PackageError(path_ + ": " + reason + sql_for_debugging(what + ": " + sql));
}

void SqliteDb::exec(const std::string& sql) {
  char* err = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &err) != SQLITE_OK) {
    std::string msg = err ? err : "unknown error";
    sqlite3_free(err);
    throw PackageError(path_ + ": " + msg + sql_for_debugging(sql));
  }
}

std::optional<int64_t> SqliteDb::query_int(const std::string& sql) {
  SqliteStatement st(*this, sql);
  if (!st.step() || st.column_is_null(0)) return std::nullopt;
  return st.column_int(0);
}

SqliteStatement::SqliteStatement(SqliteDb& db, const std::string& sql) : db_(db), sql_(sql) {
  if (sqlite3_prepare_v2(db.handle(), sql.c_str(), -1, &stmt_, nullptr) != SQLITE_OK)
    db.fail("prepare", sql);
}

SqliteStatement::~SqliteStatement() {
  sqlite3_finalize(stmt_);
}

SqliteStatement& SqliteStatement::bind(int index, int64_t value) {
  if (sqlite3_bind_int64(stmt_, index, value) != SQLITE_OK) db_.fail("bind", sql_);
  return *this;
}
SqliteStatement& SqliteStatement::bind_double(int index, double value) {
  if (sqlite3_bind_double(stmt_, index, value) != SQLITE_OK) db_.fail("bind", sql_);
  return *this;
}
SqliteStatement& SqliteStatement::bind_null(int index) {
  if (sqlite3_bind_null(stmt_, index) != SQLITE_OK) db_.fail("bind", sql_);
  return *this;
}
SqliteStatement& SqliteStatement::bind(int index, const std::string& value) {
  if (sqlite3_bind_text(stmt_, index, value.data(), static_cast<int>(value.size()),
                        SQLITE_TRANSIENT) != SQLITE_OK)
    db_.fail("bind", sql_);
  return *this;
}
SqliteStatement& SqliteStatement::bind(int index, std::span<const uint8_t> blob) {
  // An empty span may have no data pointer, which SQLite would store as NULL.
  static const uint8_t kEmpty = 0;
  if (sqlite3_bind_blob(stmt_, index, blob.empty() ? &kEmpty : blob.data(),
                        static_cast<int>(blob.size()), SQLITE_TRANSIENT) != SQLITE_OK)
    db_.fail("bind", sql_);
  return *this;
}

bool SqliteStatement::step() {
  int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  db_.fail("step", sql_);
}

void SqliteStatement::reset() {
  sqlite3_reset(stmt_);
  sqlite3_clear_bindings(stmt_);
}

int64_t SqliteStatement::column_int(int col) const {
  return sqlite3_column_int64(stmt_, col);
}
double SqliteStatement::column_double(int col) const {
  return sqlite3_column_double(stmt_, col);
}
std::string SqliteStatement::column_text(int col) const {
  auto p = sqlite3_column_text(stmt_, col);
  return p ? std::string(reinterpret_cast<const char*>(p), sqlite3_column_bytes(stmt_, col)) : "";
}
std::span<const uint8_t> SqliteStatement::column_blob(int col) const {
  auto p = static_cast<const uint8_t*>(sqlite3_column_blob(stmt_, col));
  return {p, static_cast<size_t>(sqlite3_column_bytes(stmt_, col))};
}
bool SqliteStatement::column_is_null(int col) const {
  return sqlite3_column_type(stmt_, col) == SQLITE_NULL;
}

}  // namespace tileformat
