// The one wrapper around the SQLite C API. Every call is checked; failures
// throw PackageError naming the database file and the SQL text. Used by the
// package reader/writer and by tools that need scratch databases.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

struct sqlite3;
struct sqlite3_stmt;

namespace tileformat {

class SqliteDb;

class SqliteStatement {
 public:
  SqliteStatement(SqliteDb& db, const std::string& sql);
  ~SqliteStatement();
  SqliteStatement(const SqliteStatement&) = delete;
  SqliteStatement& operator=(const SqliteStatement&) = delete;

  SqliteStatement& bind(int index, int64_t value);
  SqliteStatement& bind_double(int index, double value);
  SqliteStatement& bind_null(int index);
  SqliteStatement& bind(int index, const std::string& value);
  SqliteStatement& bind(int index, std::span<const uint8_t> blob);
  bool step();   // true while a row is available
  void reset();  // ready to bind and step again
  int64_t column_int(int col) const;
  double column_double(int col) const;
  std::string column_text(int col) const;
  std::span<const uint8_t> column_blob(int col) const;  // valid until the next step/reset
  bool column_is_null(int col) const;

 private:
  SqliteDb& db_;
  sqlite3_stmt* stmt_ = nullptr;
  std::string sql_;
};

class SqliteDb {
 public:
  enum class Mode { kReadOnly, kReadWriteCreate };
  SqliteDb(const std::string& path, Mode mode);
  ~SqliteDb();
  SqliteDb(const SqliteDb&) = delete;
  SqliteDb& operator=(const SqliteDb&) = delete;

  void exec(const std::string& sql);
  // First column of the first row of a query, if any.
  std::optional<int64_t> query_int(const std::string& sql);
  int64_t last_insert_rowid() const;
  void close();  // explicit close that reports errors (the destructor cannot)
  const std::string& path() const { return path_; }
  sqlite3* handle() { return db_; }
  [[noreturn]] void fail(const std::string& what, const std::string& sql) const;

 private:
  sqlite3* db_ = nullptr;
  std::string path_;
};

}  // namespace tileformat
