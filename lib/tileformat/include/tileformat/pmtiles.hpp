// PMTiles v3 (protomaps/PMTiles spec/v3/spec.md): one file of tiles for
// static hosting, read by clients with HTTP range requests. Written from the
// specification (docs/web.md "PMTiles"): a 127-byte header, the root
// directory, the JSON metadata, leaf directories and the tile data, in that
// order; tiles clustered (stored in tile id order), identical tiles stored
// once, consecutive ids of one content as a run; directories uncompressed
// (internal compression "none", which every client reads). The root
// directory and the header fit the first 16 KiB; larger archives get leaf
// directories, as few as make the root fit.
//
// PmtilesWriter streams: tile bytes go to a staging file as they come; it
// keeps one 24-byte entry per run of equal tiles and a hash per distinct
// content, never the tiles. The archive is written under <final>.tmp and
// renamed in finish(); a writer destroyed before finish() leaves nothing.
#pragma once

#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "tileformat/package.hpp"

namespace tileformat::pmtiles {

// Spec "Tile ID": the tiles of zooms below z, then (x, y) (XYZ, row 0 at the
// top) along the Hilbert curve of zoom z.
uint64_t tile_id(int z, uint32_t x, uint32_t y);
struct Zxy {
  int z = 0;
  uint32_t x = 0, y = 0;
  bool operator==(const Zxy&) const = default;
};
Zxy tile_zxy(uint64_t id);

enum class Compression : uint8_t { kUnknown = 0, kNone = 1, kGzip = 2, kBrotli = 3, kZstd = 4 };
enum class TileType : uint8_t { kUnknown = 0, kMvt = 1, kPng = 2, kJpeg = 3, kWebp = 4, kAvif = 5 };

// What the header says besides the sections (degrees; zooms 0..31).
struct ArchiveInfo {
  TileType tile_type = TileType::kUnknown;
  Compression tile_compression = Compression::kNone;
  int min_zoom = 0, max_zoom = 0, center_zoom = 0;
  double min_lon = -180, min_lat = -85.0511287798, max_lon = 180, max_lat = 85.0511287798;
  double center_lon = 0, center_lat = 0;
  std::string metadata_json = "{}";
};

struct Entry {
  uint64_t tile_id = 0, offset = 0;
  uint32_t length = 0, run_length = 1;
};

// The spec's directory encoding (varints: count, delta ids, run lengths,
// lengths, offsets with 0 = "right after the previous"). Exposed for tests.
std::vector<uint8_t> encode_directory(std::span<const Entry> entries);

class PmtilesWriter {
 public:
  // Throws PackageError if `final_path` exists and kFail, or if the
  // temporary files cannot be created.
  PmtilesWriter(std::string final_path, IfExists if_exists);
  ~PmtilesWriter();
  PmtilesWriter(const PmtilesWriter&) = delete;
  PmtilesWriter& operator=(const PmtilesWriter&) = delete;

  // Tiles in strictly increasing id order (std::logic_error otherwise); an
  // empty tile is not stored (clients show none there).
  void add(uint64_t tile_id, std::span<const uint8_t> bytes);
  // Writes the archive and renames it to the final path. Throws PackageError.
  void finish(const ArchiveInfo& info);

  uint64_t addressed_tiles() const { return addressed_; }
  uint64_t tile_contents() const { return contents_; }
  uint64_t bytes_written() const { return final_bytes_; }

 private:
  bool same_bytes(const Entry& stored, std::span<const uint8_t> bytes);

  std::string final_path_, temp_path_, data_path_;
  std::FILE* data_ = nullptr;
  uint64_t data_bytes_ = 0, addressed_ = 0, contents_ = 0, final_bytes_ = 0;
  bool finished_ = false, any_ = false;
  uint64_t last_id_ = 0;
  std::vector<Entry> entries_;
  std::unordered_map<uint64_t, std::vector<size_t>> by_hash_;  // content hash -> entries
  std::vector<uint8_t> compare_;
};

}  // namespace tileformat::pmtiles
