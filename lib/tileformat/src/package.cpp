// Package writer and reader (docs/tileformat.md §3).
#include "tileformat/package.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>

#include "tileformat/error.hpp"
#include "tileformat/fnv1a.hpp"

namespace tileformat {
namespace {

// A batch ends after this many tiles or bytes, whichever comes first: what a
// killed build loses at most. Both depend only on the tiles put, so commits
// fall at the same places in every run (the file's bytes depend on them).
constexpr uint64_t kBatchTiles = 512;
constexpr uint64_t kBatchBytes = uint64_t{4} << 20;

void fsync_path(const std::string& path) {
  int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

// Beside a finished temporary file while it loses its build key and is
// renamed: the key, so --resume still knows the file as its own.
std::string key_path(const std::string& temp_path) {
  return temp_path + "-key";
}

void remove_temp(const std::string& temp_path) {
  std::error_code ec;
  std::filesystem::remove(temp_path, ec);
  std::filesystem::remove(temp_path + "-journal", ec);
  std::filesystem::remove(key_path(temp_path), ec);
}

std::optional<int32_t> read_key_file(const std::string& temp_path) {
  std::ifstream in(key_path(temp_path));
  int64_t key = 0;
  if (!(in >> key)) return std::nullopt;
  return static_cast<int32_t>(key);
}

}  // namespace

int32_t build_key_hash(const std::string& build_key) {
  const auto h = static_cast<uint64_t>(static_cast<int64_t>(
      fnv1a({reinterpret_cast<const uint8_t*>(build_key.data()), build_key.size()})));
  // Never 0: a finished package's user_version is 0.
  return static_cast<int32_t>((h ^ (h >> 32)) & 0x7fffffff) | 1;
}

PackageWriter::PackageWriter(std::string final_path, IfExists if_exists)
    : PackageWriter(std::move(final_path), if_exists, "", Resume::kStartAfresh) {}

PackageWriter::PackageWriter(std::string final_path, IfExists if_exists,
                             const std::string& build_key, Resume resume)
    : final_path_(std::move(final_path)),
      temp_path_(final_path_ + ".tmp"),
      key_hash_(build_key_hash(build_key)) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(final_path_, ec) && if_exists == IfExists::kFail)
    throw PackageError(final_path_ + ": output exists; pass --force to replace it");
  if (resume == Resume::kContinue && fs::exists(temp_path_, ec) && !is_empty_database(temp_path_)) {
    resumed_ = open_existing();
    if (!resumed_)
      throw PackageError(temp_path_ +
                         ": this unfinished build was started with other inputs or options, so "
                         "--resume cannot continue it; run again without --resume to start over");
  } else {
    remove_temp(temp_path_);  // a stale temporary file from a killed run
    db_ = std::make_unique<SqliteDb>(temp_path_, SqliteDb::Mode::kReadWriteCreate);
    create_schema();
  }
  prepare_statements();
  db_->exec("BEGIN");
}

void PackageWriter::create_schema() {
  // page_size must come first: any write fixes it. Small pages waste less
  // space at the end of each blob's overflow chain. A rollback journal (not
  // fsynced) keeps the file consistent at its last commit when the process
  // is killed; it is not there to survive power loss.
  db_->exec("PRAGMA page_size = 1024; PRAGMA journal_mode = TRUNCATE; PRAGMA synchronous = OFF;");
  // One transaction: a build killed while creating the file leaves either
  // nothing (an empty database, which --resume starts afresh) or the whole
  // schema with its build key, never the identity without the key.
  db_->exec("BEGIN");
  db_->exec("PRAGMA application_id = " + std::to_string(kApplicationId));
  db_->exec("PRAGMA user_version = " + std::to_string(key_hash_));
  db_->exec(
      "CREATE TABLE metadata (name TEXT NOT NULL, value TEXT);"
      "CREATE TABLE blobs (blob_id INTEGER PRIMARY KEY, hash INTEGER NOT NULL, tile_data BLOB "
      "NOT NULL);"
      "CREATE INDEX blobs_hash ON blobs (hash);"
      "CREATE TABLE map (zoom_level INTEGER NOT NULL, tile_column INTEGER NOT NULL, tile_row "
      "INTEGER NOT NULL, blob_id INTEGER NOT NULL);"
      "CREATE VIEW tiles AS SELECT map.zoom_level AS zoom_level, map.tile_column AS tile_column, "
      "map.tile_row AS tile_row, blobs.tile_data AS tile_data FROM map JOIN blobs ON "
      "map.blob_id = blobs.blob_id;");
  db_->exec("COMMIT");
}

// Whether `path` is a database without any table (a build killed before its
// first commit; SQLite rolls its hot journal back on opening).
bool PackageWriter::is_empty_database(const std::string& path) {
  try {
    SqliteDb db(path, SqliteDb::Mode::kReadWriteCreate);
    return db.query_int("SELECT COUNT(*) FROM sqlite_master").value_or(0) == 0;
  } catch (const PackageError&) {
    return false;  // unreadable: open_existing says so
  }
}

// Opens an interrupted build's file (SQLite rolls a hot journal back on the
// first read). False if it belongs to another build.
bool PackageWriter::open_existing() {
  db_ = std::make_unique<SqliteDb>(temp_path_, SqliteDb::Mode::kReadWriteCreate);
  try {
    db_->exec("PRAGMA journal_mode = TRUNCATE; PRAGMA synchronous = OFF;");
    if (db_->query_int("PRAGMA application_id").value_or(0) != kApplicationId) return false;
    const int64_t version = db_->query_int("PRAGMA user_version").value_or(0);
    const bool has_metadata = db_->query_int("SELECT COUNT(*) FROM metadata").value_or(0) > 0;
    // Killed while being renamed: finished, without the key in its header,
    // the key beside it (commit()).
    const bool renaming = version == 0 && has_metadata && read_key_file(temp_path_) == key_hash_;
    if (version != key_hash_ && !renaming) return false;
    // A build killed after its final commit (metadata written): finished.
    finished_ = has_metadata;
    tiles_ = static_cast<uint64_t>(db_->query_int("SELECT COUNT(*) FROM map").value_or(0));
    unique_ = static_cast<uint64_t>(db_->query_int("SELECT COUNT(*) FROM blobs").value_or(0));
    blob_bytes_ = static_cast<uint64_t>(
        db_->query_int("SELECT SUM(LENGTH(tile_data)) FROM blobs").value_or(0));
  } catch (const PackageError& e) {
    throw PackageError(temp_path_ + ": the unfinished build cannot be continued (" + e.what() +
                       "); run again without --resume to start over");
  }
  return true;
}

void PackageWriter::prepare_statements() {
  find_blob_ = std::make_unique<SqliteStatement>(
      *db_, "SELECT blob_id, tile_data FROM blobs WHERE hash = ?");
  insert_blob_ =
      std::make_unique<SqliteStatement>(*db_, "INSERT INTO blobs (hash, tile_data) VALUES (?, ?)");
  insert_map_ = std::make_unique<SqliteStatement>(
      *db_, "INSERT INTO map (zoom_level, tile_column, tile_row, blob_id) VALUES (?, ?, ?, ?)");
}

PackageWriter::~PackageWriter() {
  if (committed_) return;
  find_blob_.reset();
  insert_blob_.reset();
  insert_map_.reset();
  db_.reset();
  remove_temp(temp_path_);
}

void PackageWriter::set_metadata(const std::map<std::string, std::string>& meta) {
  for (const auto& [k, v] : meta)
    set_metadata(k, v);
}

void PackageWriter::set_metadata(const std::string& name, const std::string& value) {
  metadata_[name] = value;
}

void PackageWriter::put_tile(TileId id, std::span<const uint8_t> blob) {
  // A full batch ends when the next tile comes, not right after its last
  // tile: rows a builder writes for a tile after putting it (a shard's parts)
  // join that tile's transaction, so a resumed build never skips a tile
  // committed without them.
  if (in_batch_ >= kBatchTiles || in_batch_bytes_ >= kBatchBytes) flush_batch();
  const int64_t hash = static_cast<int64_t>(fnv1a(blob));
  int64_t blob_id = -1;
  find_blob_->bind(1, hash);
  while (find_blob_->step()) {
    auto stored = find_blob_->column_blob(1);
    if (stored.size() == blob.size() && std::memcmp(stored.data(), blob.data(), blob.size()) == 0) {
      blob_id = find_blob_->column_int(0);
      break;
    }
  }
  find_blob_->reset();
  if (blob_id < 0) {
    insert_blob_->bind(1, hash).bind(2, blob);
    insert_blob_->step();
    insert_blob_->reset();
    blob_id = db_->last_insert_rowid();
    ++unique_;
    blob_bytes_ += blob.size();
  }
  const uint32_t row = TileId::flip_row(id.y, TileId::tiles_per_axis(id.z));
  insert_map_->bind(1, id.z).bind(2, id.x).bind(3, row).bind(4, blob_id);
  insert_map_->step();
  insert_map_->reset();
  ++tiles_;
  ++in_batch_;
  in_batch_bytes_ += blob.size();
}

void PackageWriter::flush_batch() {
  db_->exec("COMMIT; BEGIN");
  in_batch_ = 0;
  in_batch_bytes_ = 0;
}

void PackageWriter::checkpoint() {
  flush_batch();
}

uint64_t PackageWriter::tiles_at_zoom(int z) {
  return static_cast<uint64_t>(
      db_->query_int("SELECT COUNT(*) FROM map WHERE zoom_level = " + std::to_string(z))
          .value_or(0));
}

void PackageWriter::commit() {
  if (!finished_) {
    SqliteStatement meta(*db_, "INSERT INTO metadata (name, value) VALUES (?, ?)");
    for (const auto& [name, value] : metadata_) {  // std::map: sorted, deterministic
      meta.bind(1, name).bind(2, value);
      meta.step();
      meta.reset();
    }
    db_->exec(
        "CREATE UNIQUE INDEX map_index ON map (zoom_level, tile_column, tile_row);"
        "CREATE UNIQUE INDEX metadata_name ON metadata (name);"
        "COMMIT;");
  } else {
    db_->exec("COMMIT");
  }
  // The build key goes only now, and stays in a file beside it until the
  // rename: a build killed before that is still recognised by --resume as
  // finished (and as its own).
  // (A build killed after this step has it done already: doing it again
  // would add a write to the file's change counter, and different bytes.)
  if (db_->query_int("PRAGMA user_version").value_or(0) != 0) {
    std::ofstream key(key_path(temp_path_));
    key << key_hash_ << "\n";
    if (!key.flush()) throw PackageError(temp_path_ + ": cannot write " + key_path(temp_path_));
    db_->exec("PRAGMA user_version = 0");
  }
  db_->exec("PRAGMA journal_mode = DELETE");
  find_blob_.reset();
  insert_blob_.reset();
  insert_map_.reset();
  db_->close();
  db_.reset();
  fsync_path(temp_path_);
  std::error_code ec;
  std::filesystem::rename(temp_path_, final_path_, ec);
  if (ec)
    throw PackageError(final_path_ +
                       ": cannot rename the finished package into place: " + ec.message());
  const auto dir = std::filesystem::absolute(final_path_).parent_path();
  fsync_path(dir.string());
  std::filesystem::remove(key_path(temp_path_), ec);
  committed_ = true;
}

namespace {

// Why a file that failed to open as a package is not one, in plain words
// (SQLite's own message for anything else, e.g. "database is locked").
std::string why_not_a_package(const std::string& path, const std::string& error) {
  char head[16] = {};
  std::ifstream in(path, std::ios::binary);
  in.read(head, sizeof head);
  if (in.gcount() < 16 || std::memcmp(head, "SQLite format 3", 16) != 0)
    return "not an SQLite file";
  if (error.find("no such table") != std::string::npos)
    return "an SQLite database without the MBTiles tables (metadata, tiles)";
  const std::string prefix = path + ": ";
  return error.rfind(prefix, 0) == 0 ? error.substr(prefix.size()) : error;
}

}  // namespace

PackageReader::PackageReader(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw PackageError(path + ": no such file");
  if (!fs::is_regular_file(path, ec)) throw PackageError(path + ": not a regular file");
  db_ = std::make_unique<SqliteDb>(path, SqliteDb::Mode::kReadOnly);
  try {
    db_->exec("PRAGMA mmap_size = 2147418112");
    application_id_ = db_->query_int("PRAGMA application_id").value_or(0);
    SqliteStatement st(*db_, "SELECT name, value FROM metadata");
    while (st.step())
      metadata_[st.column_text(0)] = st.column_text(1);
    get_tile_ = std::make_unique<SqliteStatement>(
        *db_,
        "SELECT tile_data FROM tiles WHERE zoom_level = ? AND tile_column = ? AND tile_row = ?");
  } catch (const PackageError& e) {
    throw PackageError(path + ": not a tile package: " + why_not_a_package(path, e.what()) +
                       " (packages are made by globe-tiler and globe-vectorize)");
  }
}

void PackageReader::stream() {
  db_->exec("PRAGMA mmap_size = 0");
}

std::optional<std::vector<uint8_t>> PackageReader::tile(TileId id) {
  if (id.z < 0 || id.z > kMaxZoom || id.x >= 2 * TileId::tiles_per_axis(id.z) ||
      id.y >= TileId::tiles_per_axis(id.z))
    return std::nullopt;
  get_tile_->bind(1, id.z).bind(2, id.x).bind(3,
                                              TileId::flip_row(id.y, TileId::tiles_per_axis(id.z)));
  std::optional<std::vector<uint8_t>> out;
  if (get_tile_->step()) {
    auto b = get_tile_->column_blob(0);
    out.emplace(b.begin(), b.end());
  }
  get_tile_->reset();
  return out;
}

void PackageReader::for_each_tile(const std::function<void(TileId, std::span<const uint8_t>)>& fn,
                                  std::optional<int> zoom) {
  std::string sql = "SELECT zoom_level, tile_column, tile_row, tile_data FROM tiles";
  if (zoom) sql += " WHERE zoom_level = " + std::to_string(*zoom);
  sql += " ORDER BY zoom_level, tile_row DESC, tile_column";
  SqliteStatement st(*db_, sql);
  while (st.step())
    fn(checked_id(st.column_int(0), st.column_int(1), st.column_int(2)), st.column_blob(3));
}

TileId PackageReader::checked_id(int64_t z, int64_t col, int64_t row) const {
  if (z < 0 || z > kMaxZoom || col < 0 || row < 0 ||
      static_cast<uint64_t>(col) >= 2 * TileId::tiles_per_axis(static_cast<int>(z)) ||
      static_cast<uint64_t>(row) >= TileId::tiles_per_axis(static_cast<int>(z)))
    throw FormatError("3", db_->path() + ": tile index out of range: zoom " + std::to_string(z) +
                               ", column " + std::to_string(col) + ", row " + std::to_string(row));
  return {
      static_cast<int>(z), static_cast<uint32_t>(col),
      TileId::flip_row(static_cast<uint32_t>(row), TileId::tiles_per_axis(static_cast<int>(z)))};
}

bool PackageReader::has_tile(TileId id) {
  if (id.z < 0 || id.z > kMaxZoom || id.x >= 2 * TileId::tiles_per_axis(id.z) ||
      id.y >= TileId::tiles_per_axis(id.z))
    return false;
  if (!has_tile_)  // the MBTiles view, so that packages of other tools answer too
    has_tile_ = std::make_unique<SqliteStatement>(
        *db_, "SELECT 1 FROM tiles WHERE zoom_level = ? AND tile_column = ? AND tile_row = ?");
  has_tile_->reset();
  has_tile_->bind(1, id.z).bind(2, id.x).bind(3,
                                              TileId::flip_row(id.y, TileId::tiles_per_axis(id.z)));
  const bool found = has_tile_->step();
  has_tile_->reset();
  return found;
}

std::vector<TileId> PackageReader::tile_ids(int zoom) {
  SqliteStatement st(*db_,
                     "SELECT tile_column, tile_row FROM tiles WHERE zoom_level = ? "
                     "ORDER BY tile_row DESC, tile_column");
  st.bind(1, zoom);
  std::vector<TileId> out;
  while (st.step())
    out.push_back(checked_id(zoom, st.column_int(0), st.column_int(1)));
  return out;
}

std::vector<ZoomSummary> PackageReader::zoom_summaries() {
  std::vector<ZoomSummary> out;
  SqliteStatement st(*db_,
                     "SELECT map.zoom_level, COUNT(*), SUM(LENGTH(blobs.tile_data)), "
                     "MIN(tile_column), MAX(tile_column), MIN(tile_row), MAX(tile_row) FROM map "
                     "JOIN blobs ON map.blob_id = blobs.blob_id GROUP BY map.zoom_level "
                     "ORDER BY map.zoom_level");
  while (st.step()) {
    // The corners go through checked_id: a zoom or index out of range is a
    // format error, never a shift by a stored number.
    const int64_t zoom = st.column_int(0);
    const TileId low = checked_id(zoom, st.column_int(3), st.column_int(6));
    const TileId high = checked_id(zoom, st.column_int(4), st.column_int(5));
    ZoomSummary s;
    s.zoom = low.z;
    s.tiles = static_cast<uint64_t>(st.column_int(1));
    s.bytes = static_cast<uint64_t>(st.column_int(2));
    s.min_x = low.x;
    s.max_x = high.x;
    s.min_y = low.y;
    s.max_y = high.y;
    out.push_back(s);
  }
  return out;
}

const std::string& PackageReader::path() const {
  return db_->path();
}

uint64_t PackageReader::unique_blobs() {
  return static_cast<uint64_t>(db_->query_int("SELECT COUNT(*) FROM blobs").value_or(0));
}

}  // namespace tileformat
