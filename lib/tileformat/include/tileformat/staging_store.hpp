// Scratch storage for a build (the staging/resume protocol every raster
// builder shares, docs/robustness.md): per-level intermediate blocks live in
// a temporary SQLite file (not in memory), so peak memory does not grow with
// the input. Deleted when the build ends, successfully or not;
// a killed build leaves it behind, consistent at its last commit (rollback
// journal), with a checkpoint saying how far the build had got, for --resume.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tileformat/package.hpp"
#include "tileformat/sqlite_db.hpp"
#include "tileformat/tile_id.hpp"

namespace tileformat {

// A builder's name for one kind of intermediate data (a small integer, 0..255:
// the builder's stage enum); each (stage, zoom) is its own table.
using StageTag = int;

// How far a build got: pass `pass` of zoom `z` has consumed its first `done`
// work items, which put `puts` tiles of zoom z into the package (the meaning
// of passes and items is the builder's).
struct StageCheckpoint {
  int z = 0;
  int pass = 0;
  uint64_t done = 0;
  uint64_t puts = 0;
};

class StagingStore {
 public:
  // `key` identifies the build (see tileformat::build_key_hash). With
  // Resume::kContinue, an existing store made with the same key is kept; otherwise
  // the store starts empty.
  StagingStore(std::string path, int32_t key, Resume resume);
  ~StagingStore();

  // The last committed checkpoint of a kept store; nullopt for a new one.
  std::optional<StageCheckpoint> checkpoint();
  // Every committed checkpoint of zoom z, oldest first.
  std::vector<StageCheckpoint> checkpoints(int z);

  void put(StageTag stage, TileId id, const std::vector<uint8_t>& data);
  std::optional<std::vector<uint8_t>> get(StageTag stage, TileId id);
  // Tiles of one stage and zoom, sorted by (y, x).
  std::vector<TileId> list(StageTag stage, int z);
  void drop(StageTag stage, int z);
  void commit();  // ends the current write transaction
  // Commits together with a checkpoint (atomically).
  void commit(const StageCheckpoint& at);
  // The same, unless the store committed less than a second ago: called
  // where a batch of work begins, so a killed build loses little work and a
  // running one little time.
  void commit_if_due(const StageCheckpoint& at);

 private:
  struct Table {
    std::unique_ptr<SqliteStatement> put, get;
  };
  Table& table(StageTag stage, int z);  // created on first use

  std::string path_;
  std::unique_ptr<SqliteDb> db_;
  std::map<std::pair<int, int>, Table> tables_;  // (stage, z)
  std::chrono::steady_clock::time_point last_commit_ = std::chrono::steady_clock::now();
};

}  // namespace tileformat
