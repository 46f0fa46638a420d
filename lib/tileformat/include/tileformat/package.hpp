// Packages: one SQLite file with the MBTiles 1.3 schema (docs/tileformat.md §3).
//
// PackageWriter builds a package under a temporary name (<final>.tmp) and
// renames it to the final name only in commit(); destroying an uncommitted
// writer deletes the temporary file, so the final name only ever holds a
// complete package. Identical blobs are stored once.
//
// Crash safety and resume (docs/robustness.md): tiles are committed in
// batches (512 tiles or 4 MiB) through a rollback journal, so a killed build leaves
// <final>.tmp holding every batch committed before the kill. A full batch is
// committed when the next tile is put, so rows written on db() right after a
// tile are committed with it. A writer opened
// with `resume` keeps that file (its header's user_version holds a hash of
// the build key, so a build with other inputs or options cannot continue
// it); the builder then skips the tiles already there (tiles_at_zoom) and
// puts the rest in the same order, which yields the same bytes as an
// uninterrupted run.
//
// PackageReader opens a package read-only with memory mapping. Spans it
// returns point into SQLite's buffers and stay valid only until the next call.
// Its connection is serialized: one thread may call tile() while others run
// their own statements on db(); everything then reads the file that was open
// when the reader was made, even if the path is replaced meanwhile.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tileformat/sqlite_db.hpp"
#include "tileformat/tile_id.hpp"
#include "tileformat/tile_reader.hpp"

namespace tileformat {

inline constexpr int64_t kApplicationId = 0x4d504258;  // "MPBX"

// What a writer does with a file already under the final name.
enum class IfExists { kFail, kOverwrite };
// What a writer does with the temporary file of an interrupted build.
enum class Resume { kStartAfresh, kContinue };

class PackageWriter {
 public:
  // Throws PackageError if `final_path` exists and kFail, or if the
  // temporary file cannot be created. A stale temporary file is deleted.
  PackageWriter(std::string final_path, IfExists if_exists);
  // With kContinue, an existing temporary file started with the same
  // `build_key` is continued (resumed() is then true); one started with
  // another key throws PackageError. With kStartAfresh, a stale one is deleted.
  PackageWriter(std::string final_path, IfExists if_exists, const std::string& build_key,
                Resume resume);
  ~PackageWriter();  // rolls back (deletes the temporary file) unless committed
  PackageWriter(const PackageWriter&) = delete;
  PackageWriter& operator=(const PackageWriter&) = delete;

  void set_metadata(const std::string& name, const std::string& value);
  // Every key of `meta` (tileformat::to_metadata of a kind's metadata).
  void set_metadata(const std::map<std::string, std::string>& meta);
  // Stores the tile; a blob identical to one stored before is shared.
  void put_tile(TileId id, std::span<const uint8_t> blob);
  // Commits the tiles put so far now (e.g. at the end of a build stage whose
  // scratch data is about to be dropped).
  void checkpoint();
  // Writes metadata, builds indexes, syncs, and renames to the final path.
  void commit();

  // Whether an interrupted build's temporary file was continued.
  bool resumed() const { return resumed_; }
  // build_key_hash of this build's key (for scratch files that belong to it).
  int32_t key_hash() const { return key_hash_; }
  // Tiles of zoom z committed before this writer was opened plus those put since.
  uint64_t tiles_at_zoom(int z);

  const std::string& temp_path() const { return temp_path_; }
  uint64_t tiles_written() const { return tiles_; }
  uint64_t unique_blobs() const { return unique_; }
  uint64_t blob_bytes() const { return blob_bytes_; }

 private:
  void create_schema();
  // The database being built, for the tables beyond the tiles (the features
  // and shard tables, by their own classes). Writes join the open transaction.
  friend class FeatureTableWriter;
  friend class LabelTableWriter;
  friend class ShardTableWriter;
  friend struct PackageTestAccess;  // tests/package_test.cpp
  SqliteDb& db() { return *db_; }
  bool open_existing();
  static bool is_empty_database(const std::string& path);
  void prepare_statements();
  void flush_batch();
  std::string final_path_, temp_path_;
  std::unique_ptr<SqliteDb> db_;
  std::unique_ptr<SqliteStatement> find_blob_, insert_blob_, insert_map_;
  std::map<std::string, std::string> metadata_;
  uint64_t tiles_ = 0, unique_ = 0, blob_bytes_ = 0, in_batch_ = 0, in_batch_bytes_ = 0;
  int32_t key_hash_ = 0;
  bool committed_ = false, resumed_ = false, finished_ = false;
};

// The hash stored in a temporary package's header while it is being built.
int32_t build_key_hash(const std::string& build_key);

struct ZoomSummary {
  int zoom = 0;
  uint64_t tiles = 0;
  uint64_t bytes = 0;  // sum over tiles (shared blobs counted per tile)
  uint32_t min_x = 0, max_x = 0, min_y = 0, max_y = 0;  // XYZ
};

class PackageReader final : public TileReader {
 public:
  explicit PackageReader(const std::string& path);  // throws PackageError

  // Reads through SQLite's small page cache instead of the memory map the
  // reader starts with (which suits the viewer and the server, who read the
  // same tiles again): for one pass over a large package, whose mapped pages
  // would otherwise stay in the process's resident memory, counted by a
  // cluster scheduler's limit, up to the whole file.
  void stream();

  const std::map<std::string, std::string>& metadata() const override { return metadata_; }
  int64_t application_id() const { return application_id_; }

  // Copy of the tile blob, or nullopt if the package has none at `id`.
  std::optional<std::vector<uint8_t>> tile(TileId id) override;
  // Calls fn for every tile in (zoom, row, column) order of the TMS index.
  void for_each_tile(const std::function<void(TileId, std::span<const uint8_t>)>& fn,
                     std::optional<int> zoom = std::nullopt);
  // Whether the package has a tile at `id` (without reading it). One thread
  // at a time; it may run while another thread calls tile().
  bool has_tile(TileId id) override;
  // The tiles of one zoom, in (y, x) order; throws FormatError for an index
  // outside the zoom's range.
  std::vector<TileId> tile_ids(int zoom) override;
  std::vector<ZoomSummary> zoom_summaries();
  uint64_t unique_blobs();
  // The file this reader opened, for messages.
  const std::string& path() const override;
  PackageReader* package() override { return this; }

 private:
  // The tables beyond the tiles (the features and shard tables) are read by
  // their own classes; nothing else issues SQL (docs/architecture.md rule 1).
  friend class FeatureTableReader;
  friend class LabelTableReader;
  friend class ShardTableReader;
  friend struct PackageTestAccess;  // tests/package_test.cpp
  SqliteDb& db() { return *db_; }
  TileId checked_id(int64_t z, int64_t column, int64_t row) const;
  std::unique_ptr<SqliteDb> db_;
  std::unique_ptr<SqliteStatement> get_tile_, has_tile_;
  std::map<std::string, std::string> metadata_;
  int64_t application_id_ = 0;
};

}  // namespace tileformat
