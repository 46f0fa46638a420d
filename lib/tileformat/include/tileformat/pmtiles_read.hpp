// Reading PMTiles v3 (protomaps/PMTiles spec/v3/spec.md), the other half of
// pmtiles.hpp: the 127-byte header, a directory's entries (after the caller
// has undone the archive's internal compression) and the lookup of a tile id
// in a directory. No I/O: globe-view's PMTiles source
// (viewer/data/pmtiles_fetcher.hpp) reads the bytes over HTTP ranges. Every
// malformed input is a PmtilesError saying what is wrong (the bytes come
// from the network).
#pragma once

#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

#include "tileformat/pmtiles.hpp"

namespace tileformat::pmtiles {

inline constexpr size_t kHeaderSize = 127;

struct PmtilesError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Header {
  uint64_t root_offset = 0, root_length = 0, metadata_offset = 0, metadata_length = 0;
  uint64_t leaf_offset = 0, leaf_length = 0, data_offset = 0, data_length = 0;
  uint64_t addressed_tiles = 0, tile_entries = 0, tile_contents = 0;
  bool clustered = false;
  Compression internal_compression = Compression::kUnknown;
  ArchiveInfo info;  // tile type and compression, zooms, bounds, centre (metadata_json unset)
};

// Throws PmtilesError: fewer than 127 bytes, not "PMTiles", not version 3.
Header decode_header(std::span<const uint8_t> bytes);
// An uncompressed directory; throws PmtilesError for a truncated or
// inconsistent one (more entries than bytes, ids that overflow).
std::vector<Entry> decode_directory(std::span<const uint8_t> bytes);
// The entry covering `tile_id`: a tile (run_length > 0, tile_id within its
// run) or a leaf directory (run_length == 0, the last entry at or before
// it); nullptr when the directory has neither.
const Entry* find_entry(const std::vector<Entry>& entries, uint64_t tile_id);

}  // namespace tileformat::pmtiles
