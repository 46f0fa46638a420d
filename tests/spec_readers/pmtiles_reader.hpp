// Independent PMTiles v3 reader, written only from the public specification
// (protomaps/PMTiles, spec/v3/spec.md). The tests use it to check archives that
// the project writes; it shares no code with the project's own exporter.
//
// Section references ("spec 3.2", "spec 4.2", ...) are to that document:
//   2    Overview: header, root directory, metadata, leaf directories, tile data.
//   3    Header: 127 bytes, little-endian, at the start of the archive.
//   3.3  Compression enum.    3.4  Positions (degrees * 10,000,000, int32).
//   4    Directories: root plus optional leaves; header + root <= 16,384 bytes.
//   4.1  Entries (TileID, Offset, Length, RunLength); TileID is a Hilbert index.
//   4.2  Encoding / 4.3 Decoding (varints, columnar, delta ids, offset 0 rule).
//
// Bytes are passed as std::string_view (a std::string holding a file works
// directly). Every problem is reported as std::runtime_error("pmtiles: ...")
// naming what is wrong and where.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "spec_readers/gunzip.hpp"

namespace spec_readers::pmtiles {

// ---------------------------------------------------------------------------
// Spec 3.2 / 3.3: enums stored in the header.

// Spec 3.3: used both for Internal Compression (IC, byte 97) and Tile
// Compression (TC, byte 98).
enum class Compression : std::uint8_t { Unknown = 0, None = 1, Gzip = 2, Brotli = 3, Zstd = 4 };

// Spec 3.2 "Tile Type (TT)", byte 99.
enum class TileType : std::uint8_t {
  Unknown = 0,
  Mvt = 1,
  Png = 2,
  Jpeg = 3,
  Webp = 4,
  Avif = 5,
  MapLibreVectorTile = 6,
};

// Spec 3.1 / 3.2: every field of the 127-byte header.
struct Header {
  std::uint8_t version = 0;                 // byte 7, always 3
  std::uint64_t root_dir_offset = 0;        // byte 8, from start of archive
  std::uint64_t root_dir_length = 0;        // byte 16
  std::uint64_t metadata_offset = 0;        // byte 24
  std::uint64_t metadata_length = 0;        // byte 32
  std::uint64_t leaf_dirs_offset = 0;       // byte 40
  std::uint64_t leaf_dirs_length = 0;       // byte 48, 0 = no leaf directories
  std::uint64_t tile_data_offset = 0;       // byte 56
  std::uint64_t tile_data_length = 0;       // byte 64
  std::uint64_t addressed_tiles_count = 0;  // byte 72, 0 = unknown
  std::uint64_t tile_entries_count = 0;     // byte 80, 0 = unknown
  std::uint64_t tile_contents_count = 0;    // byte 88, 0 = unknown
  bool clustered = false;                   // byte 96, 0x00 or 0x01
  Compression internal_compression{};       // byte 97
  Compression tile_compression{};           // byte 98
  TileType tile_type{};                     // byte 99
  std::uint8_t min_zoom = 0;                // byte 100
  std::uint8_t max_zoom = 0;                // byte 101
  std::int32_t min_lon_e7 = 0;              // byte 102, min position: lon then lat
  std::int32_t min_lat_e7 = 0;              // byte 106
  std::int32_t max_lon_e7 = 0;              // byte 110, max position
  std::int32_t max_lat_e7 = 0;              // byte 114
  std::uint8_t center_zoom = 0;             // byte 118
  std::int32_t center_lon_e7 = 0;           // byte 119, center position
  std::int32_t center_lat_e7 = 0;           // byte 123

  // Spec 3.4 "Decoding": divide the int32 by 10,000,000.
  static double degrees(std::int32_t e7) { return e7 / 10000000.0; }
  double min_lon() const { return degrees(min_lon_e7); }
  double min_lat() const { return degrees(min_lat_e7); }
  double max_lon() const { return degrees(max_lon_e7); }
  double max_lat() const { return degrees(max_lat_e7); }
  double center_lon() const { return degrees(center_lon_e7); }
  double center_lat() const { return degrees(center_lat_e7); }
};

// Spec 4.1: one directory entry. run_length == 0 marks a leaf directory whose
// offset is relative to the leaf directories section; otherwise the entry is a
// tile (repeated run_length times) whose offset is relative to the tile data.
struct Entry {
  std::uint64_t tile_id = 0;
  std::uint64_t offset = 0;
  std::uint32_t length = 0;
  std::uint32_t run_length = 0;

  bool operator==(const Entry& o) const {
    return tile_id == o.tile_id && offset == o.offset && length == o.length &&
           run_length == o.run_length;
  }
};

struct TileCoord {
  std::uint8_t z = 0;
  std::uint32_t x = 0, y = 0;
  bool operator==(const TileCoord& o) const { return z == o.z && x == o.x && y == o.y; }
};

constexpr std::size_t kHeaderSize = 127;          // spec 3
constexpr std::uint64_t kRootLimitBytes = 16384;  // spec 2 / 4: header + root
constexpr int kMaxTileZoom = 31;                  // largest zoom whose ids fit in uint64
constexpr int kMaxDirectoryDepth = 4;             // spec 4 discourages > 1 leaf level

namespace detail {

[[noreturn]] inline void fail(const std::string& what) {
  throw std::runtime_error("pmtiles: " + what);
}

inline std::uint64_t read_le(std::string_view bytes, std::size_t at, int width) {
  std::uint64_t value = 0;
  for (int i = width - 1; i >= 0; --i) {
    value = (value << 8) | static_cast<unsigned char>(bytes[at + i]);
  }
  return value;
}

inline std::int32_t read_le_i32(std::string_view bytes, std::size_t at) {
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(read_le(bytes, at, 4)));
}

// True when [offset, offset + length) lies inside [0, size), without overflow.
inline bool range_inside(std::uint64_t offset, std::uint64_t length, std::uint64_t size) {
  return offset <= size && length <= size - offset;
}

// gzip (RFC 1952): one gzip member, nothing after it (spec_readers/gunzip.hpp).
inline std::string gunzip(std::string_view in, const std::string& what,
                          std::size_t max_output = std::size_t{1} << 31) {
  return spec_readers::gunzip(in, "pmtiles: " + what + ": ", max_output);
}

// Spec 4.2: "little-endian variable-width integer" = protobuf varint: 7 bits
// per byte, least significant group first, high bit set on all but the last.
struct VarintReader {
  std::string_view bytes;
  std::string what;  // e.g. "root directory", for error messages
  std::size_t pos = 0;

  std::uint64_t next(const char* field) {
    std::uint64_t value = 0;
    const std::size_t start = pos;
    for (int shift = 0;; shift += 7) {
      if (pos >= bytes.size()) {
        fail(what + ": truncated varint for " + field + " at byte " + std::to_string(start) +
             " of the decompressed directory (size " + std::to_string(bytes.size()) + ")");
      }
      const auto byte = static_cast<unsigned char>(bytes[pos++]);
      if (shift == 63 && (byte & 0x7e) != 0) {
        fail(what + ": varint for " + std::string(field) + " at byte " + std::to_string(start) +
             " overflows 64 bits");
      }
      value |= static_cast<std::uint64_t>(byte & 0x7f) << shift;
      if ((byte & 0x80) == 0) return value;
      if (shift == 63) {
        fail(what + ": varint for " + std::string(field) + " at byte " + std::to_string(start) +
             " is longer than 10 bytes");
      }
    }
  }
};

}  // namespace detail

// ---------------------------------------------------------------------------
// Spec 4.1 "TileID": a cumulative position on the series of Hilbert curves
// starting at zoom 0. Zoom z starts at sum_{i<z} 4^i; inside the zoom the
// position is the Hilbert index d of (x, y) on a 2^z x 2^z grid, with the curve
// orientation fixed by the spec's table: (1,0,0)=1, (1,0,1)=2, (1,1,1)=3,
// (1,1,0)=4, i.e. quadrant order (0,0) (0,1) (1,1) (1,0) -- the classic
// xy2d / d2xy construction (en.wikipedia.org/wiki/Hilbert_curve).

// First tile id of zoom z: 0, 1, 5, 21, 85, ... = (4^z - 1) / 3.
inline std::uint64_t first_tile_id_of_zoom(int z) {
  std::uint64_t base = 0;
  for (int i = 0; i < z; ++i)
    base += std::uint64_t{1} << (2 * i);
  return base;
}

namespace detail {
// Hilbert "rot": reflect and/or transpose the quadrant so that the sub-curve
// inside it has the same orientation as the parent curve.
inline void hilbert_rotate(std::uint64_t s, std::uint64_t& x, std::uint64_t& y, std::uint64_t rx,
                           std::uint64_t ry) {
  if (ry == 0) {
    if (rx == 1) {
      x = s - 1 - x;
      y = s - 1 - y;
    }
    std::swap(x, y);
  }
}
}  // namespace detail

inline std::uint64_t zxy_to_tile_id(int z, std::uint32_t x, std::uint32_t y) {
  if (z < 0 || z > kMaxTileZoom) {
    detail::fail("zoom " + std::to_string(z) + " is outside 0.." + std::to_string(kMaxTileZoom));
  }
  const std::uint64_t n = std::uint64_t{1} << z;
  if (x >= n || y >= n) {
    detail::fail("tile " + std::to_string(z) + "/" + std::to_string(x) + "/" + std::to_string(y) +
                 " is outside the 2^z x 2^z grid");
  }
  std::uint64_t hx = x, hy = y, d = 0;
  for (std::uint64_t s = n / 2; s > 0; s /= 2) {
    const std::uint64_t rx = (hx & s) ? 1 : 0;
    const std::uint64_t ry = (hy & s) ? 1 : 0;
    d += s * s * ((3 * rx) ^ ry);
    // Only the bits below s matter from here on, so reflecting within the
    // current square of side s is enough.
    hx &= s - 1;
    hy &= s - 1;
    detail::hilbert_rotate(s, hx, hy, rx, ry);
  }
  return first_tile_id_of_zoom(z) + d;
}

inline TileCoord tile_id_to_zxy(std::uint64_t tile_id) {
  std::uint64_t base = 0;
  for (int z = 0; z <= kMaxTileZoom; ++z) {
    const std::uint64_t tiles_in_zoom = std::uint64_t{1} << (2 * z);
    if (tile_id - base < tiles_in_zoom) {
      const std::uint64_t n = std::uint64_t{1} << z;
      std::uint64_t t = tile_id - base, x = 0, y = 0;
      for (std::uint64_t s = 1; s < n; s *= 2) {
        const std::uint64_t rx = 1 & (t / 2);
        const std::uint64_t ry = 1 & (t ^ rx);
        detail::hilbert_rotate(s, x, y, rx, ry);
        x += s * rx;
        y += s * ry;
        t /= 4;
      }
      return TileCoord{static_cast<std::uint8_t>(z), static_cast<std::uint32_t>(x),
                       static_cast<std::uint32_t>(y)};
    }
    base += tiles_in_zoom;
  }
  detail::fail("tile id " + std::to_string(tile_id) + " is beyond zoom " +
               std::to_string(kMaxTileZoom));
}

// ---------------------------------------------------------------------------
// Spec 3: the header, with the checks every reader needs before trusting it.
// Throws for: short file, bad magic (3.2 "Magic Number"), version != 3,
// clustered byte not 0/1, compression enum outside 3.3, max zoom < min zoom,
// any section outside the file, an empty root directory, and a root directory
// that does not end within the first 16,384 bytes (spec 2 and 4: "the size of
// the header plus the compressed size of the root directory MUST NOT exceed
// 16384 bytes", i.e. at most 16,257 bytes right after the header).
inline Header read_header(std::string_view file) {
  using detail::fail;
  using detail::read_le;
  if (file.size() < kHeaderSize) {
    fail("file is " + std::to_string(file.size()) + " bytes, shorter than the 127-byte header");
  }
  if (file.substr(0, 7) != "PMTiles") fail("bad magic at byte 0: expected \"PMTiles\"");
  Header h;
  h.version = static_cast<std::uint8_t>(file[7]);
  if (h.version != 3) {
    fail("unsupported spec version " + std::to_string(h.version) + " at byte 7 (expected 3)");
  }
  h.root_dir_offset = read_le(file, 8, 8);
  h.root_dir_length = read_le(file, 16, 8);
  h.metadata_offset = read_le(file, 24, 8);
  h.metadata_length = read_le(file, 32, 8);
  h.leaf_dirs_offset = read_le(file, 40, 8);
  h.leaf_dirs_length = read_le(file, 48, 8);
  h.tile_data_offset = read_le(file, 56, 8);
  h.tile_data_length = read_le(file, 64, 8);
  h.addressed_tiles_count = read_le(file, 72, 8);
  h.tile_entries_count = read_le(file, 80, 8);
  h.tile_contents_count = read_le(file, 88, 8);
  const auto clustered = static_cast<std::uint8_t>(file[96]);
  if (clustered > 1) {
    fail("clustered flag at byte 96 is " + std::to_string(clustered) + " (expected 0 or 1)");
  }
  h.clustered = clustered == 1;
  for (int at : {97, 98}) {
    if (static_cast<std::uint8_t>(file[at]) > 4) {
      fail("compression enum at byte " + std::to_string(at) + " is " +
           std::to_string(static_cast<std::uint8_t>(file[at])) + " (spec 3.3 defines 0..4)");
    }
  }
  h.internal_compression = static_cast<Compression>(file[97]);
  h.tile_compression = static_cast<Compression>(file[98]);
  h.tile_type = static_cast<TileType>(file[99]);
  h.min_zoom = static_cast<std::uint8_t>(file[100]);
  h.max_zoom = static_cast<std::uint8_t>(file[101]);
  if (h.max_zoom < h.min_zoom) {
    fail("max zoom " + std::to_string(h.max_zoom) + " (byte 101) is below min zoom " +
         std::to_string(h.min_zoom) + " (byte 100)");
  }
  h.min_lon_e7 = detail::read_le_i32(file, 102);
  h.min_lat_e7 = detail::read_le_i32(file, 106);
  h.max_lon_e7 = detail::read_le_i32(file, 110);
  h.max_lat_e7 = detail::read_le_i32(file, 114);
  h.center_zoom = static_cast<std::uint8_t>(file[118]);
  h.center_lon_e7 = detail::read_le_i32(file, 119);
  h.center_lat_e7 = detail::read_le_i32(file, 123);

  struct Section {
    const char* name;
    std::uint64_t offset, length;
  };
  for (const Section& s : {Section{"root directory", h.root_dir_offset, h.root_dir_length},
                           Section{"metadata", h.metadata_offset, h.metadata_length},
                           Section{"leaf directories", h.leaf_dirs_offset, h.leaf_dirs_length},
                           Section{"tile data", h.tile_data_offset, h.tile_data_length}}) {
    if (!detail::range_inside(s.offset, s.length, file.size())) {
      fail(std::string(s.name) + " section [" + std::to_string(s.offset) + ", +" +
           std::to_string(s.length) + ") is out of bounds of the " + std::to_string(file.size()) +
           "-byte file");
    }
  }
  if (h.root_dir_length == 0) fail("root directory length is 0 (a directory is never empty)");
  if (h.root_dir_offset + h.root_dir_length > kRootLimitBytes) {
    fail("root directory ends at byte " + std::to_string(h.root_dir_offset + h.root_dir_length) +
         " (length " + std::to_string(h.root_dir_length) +
         "), beyond the first 16384 bytes; header + root directory must fit in 16384 bytes");
  }
  return h;
}

// Undo a compression from spec 3.3. Only None and gzip are supported here.
inline std::string decompress(std::string_view stored, Compression compression,
                              const std::string& what) {
  switch (compression) {
    case Compression::None:
      return std::string(stored);
    case Compression::Gzip:
      return detail::gunzip(stored, what);
    default:
      detail::fail(what + ": compression " + std::to_string(static_cast<int>(compression)) +
                   " is not supported by this reader (only 1 = none and 2 = gzip)");
  }
}

// Spec 4.3 / appendix A.2: decode one directory as stored in the file.
// `what` names the directory in error messages. Throws for an entry count of 0
// (4.2: MUST be > 0), non-increasing tile ids (delta 0 after the first entry),
// lengths of 0 (4.1: MUST be > 0), run lengths or lengths above uint32, a first
// offset encoded as 0 (nothing precedes it), and trailing bytes.
inline std::vector<Entry> decode_directory(std::string_view stored, Compression compression,
                                           const std::string& what = "directory") {
  using detail::fail;
  const std::string decompressed = decompress(stored, compression, what);
  detail::VarintReader in{decompressed, what};

  const std::uint64_t count = in.next("the number of entries");
  if (count == 0) fail(what + ": number of entries is 0 (must be > 0)");
  // Every entry needs at least 4 varint bytes; reject absurd counts early.
  if (count > decompressed.size() / 4) {
    fail(what + ": claims " + std::to_string(count) + " entries but has only " +
         std::to_string(decompressed.size()) + " bytes");
  }
  std::vector<Entry> entries(count);

  // 4.2 "TileIDs": delta from the previous TileID (the first from 0).
  std::uint64_t last_id = 0;
  for (std::uint64_t i = 0; i < count; ++i) {
    const std::size_t at = in.pos;
    const std::uint64_t delta = in.next("a tile id delta");
    if (i > 0 && delta == 0) {
      fail(what + ": non-increasing tile ids: entry " + std::to_string(i) + " repeats tile id " +
           std::to_string(last_id) + " (delta 0 at byte " + std::to_string(at) + ")");
    }
    if (delta > UINT64_MAX - last_id)
      fail(what + ": tile id overflows at entry " + std::to_string(i));
    last_id += delta;
    entries[i].tile_id = last_id;
  }
  // 4.2 "RunLengths": as is (0 = leaf directory).
  for (std::uint64_t i = 0; i < count; ++i) {
    const std::uint64_t run_length = in.next("a run length");
    if (run_length > UINT32_MAX) {
      fail(what + ": run length " + std::to_string(run_length) + " of entry " + std::to_string(i) +
           " does not fit in 32 bits");
    }
    entries[i].run_length = static_cast<std::uint32_t>(run_length);
  }
  // 4.2 "Lengths": as is, MUST be > 0.
  for (std::uint64_t i = 0; i < count; ++i) {
    const std::uint64_t length = in.next("a length");
    if (length == 0 || length > UINT32_MAX) {
      fail(what + ": length " + std::to_string(length) + " of entry " + std::to_string(i) +
           " (tile id " + std::to_string(entries[i].tile_id) + ") is not in 1..2^32-1");
    }
    entries[i].length = static_cast<std::uint32_t>(length);
  }
  // 4.2 "Offsets": 0 = previous offset + previous length; otherwise offset + 1.
  for (std::uint64_t i = 0; i < count; ++i) {
    const std::size_t at = in.pos;
    const std::uint64_t value = in.next("an offset");
    if (value == 0) {
      if (i == 0) {
        fail(what + ": first entry's offset is encoded as 0 (\"same as previous\") at byte " +
             std::to_string(at) + ", but there is no previous entry");
      }
      entries[i].offset = entries[i - 1].offset + entries[i - 1].length;
    } else {
      entries[i].offset = value - 1;
    }
  }
  if (in.pos != decompressed.size()) {
    fail(what + ": " + std::to_string(decompressed.size() - in.pos) +
         " trailing bytes after the last offset (at byte " + std::to_string(in.pos) + ")");
  }
  return entries;
}

inline std::vector<Entry> read_root_directory(std::string_view file) {
  const Header h = read_header(file);
  return decode_directory(file.substr(h.root_dir_offset, h.root_dir_length), h.internal_compression,
                          "root directory");
}

// Spec 5: the JSON metadata, decompressed with the internal compression.
// (Its content is not parsed here.)
inline std::string read_metadata(std::string_view file) {
  const Header h = read_header(file);
  return decompress(file.substr(h.metadata_offset, h.metadata_length), h.internal_compression,
                    "metadata");
}

namespace detail {

// Reads the leaf directory that `leaf` (run_length 0) points at. Spec 4.1:
// its offset is relative to the leaf directories section.
inline std::vector<Entry> read_leaf(std::string_view file, const Header& h, const Entry& leaf) {
  const std::string what = "leaf directory for tile id " + std::to_string(leaf.tile_id);
  if (!range_inside(leaf.offset, leaf.length, h.leaf_dirs_length)) {
    fail(what + ": bytes [" + std::to_string(leaf.offset) + ", +" + std::to_string(leaf.length) +
         ") are out of bounds of the " + std::to_string(h.leaf_dirs_length) +
         "-byte leaf directories section");
  }
  std::vector<Entry> entries = decode_directory(
      file.substr(h.leaf_dirs_offset + leaf.offset, leaf.length), h.internal_compression, what);
  // Spec 4.1: the leaf entry's TileID is "the first tile in the leaf directory".
  if (entries.front().tile_id != leaf.tile_id) {
    fail(what + ": first entry has tile id " + std::to_string(entries.front().tile_id) +
         ", expected the leaf entry's tile id " + std::to_string(leaf.tile_id));
  }
  return entries;
}

inline void check_tile_inside_data(const Header& h, const Entry& e) {
  if (!range_inside(e.offset, e.length, h.tile_data_length)) {
    fail("tile data for tile id " + std::to_string(e.tile_id) + " at [" + std::to_string(e.offset) +
         ", +" + std::to_string(e.length) + ") is outside the tile data section of length " +
         std::to_string(h.tile_data_length));
  }
}

inline void expand(std::string_view file, const Header& h, const std::vector<Entry>& directory,
                   int depth, std::vector<Entry>& out) {
  for (const Entry& e : directory) {
    if (e.run_length > 0) {
      out.push_back(e);
    } else {
      if (depth >= kMaxDirectoryDepth) {
        fail("leaf directories nested deeper than " + std::to_string(kMaxDirectoryDepth) +
             " levels at tile id " + std::to_string(e.tile_id));
      }
      expand(file, h, read_leaf(file, h, e), depth + 1, out);
    }
  }
}

}  // namespace detail

// Every tile entry (run_length > 0) of the archive in directory order, with
// leaf directories expanded. Throws if, across the whole archive, tile ids are
// not strictly increasing, runs overlap (tile_id + run_length > next tile_id),
// or a tile lies outside the tile data section.
inline std::vector<Entry> read_all_entries(std::string_view file) {
  const Header h = read_header(file);
  const std::vector<Entry> root = decode_directory(
      file.substr(h.root_dir_offset, h.root_dir_length), h.internal_compression, "root directory");
  std::vector<Entry> out;
  detail::expand(file, h, root, 0, out);
  for (std::size_t i = 0; i < out.size(); ++i) {
    detail::check_tile_inside_data(h, out[i]);
    if (i == 0) continue;
    const Entry& prev = out[i - 1];
    if (out[i].tile_id <= prev.tile_id) {
      detail::fail("non-increasing tile ids after expanding leaf directories: tile id " +
                   std::to_string(out[i].tile_id) + " follows " + std::to_string(prev.tile_id));
    }
    if (out[i].tile_id - prev.tile_id < prev.run_length) {
      detail::fail("run of tile id " + std::to_string(prev.tile_id) + " (run length " +
                   std::to_string(prev.run_length) + ") overlaps tile id " +
                   std::to_string(out[i].tile_id));
    }
  }
  return out;
}

// Spec 4.1: find the entry for a tile: the last entry with TileID <= id; a
// tile entry covers ids [TileID, TileID + RunLength), a leaf entry is searched
// recursively. Returns the stored tile bytes (still with the header's tile
// compression), or nullopt when the archive has no such tile.
inline std::optional<std::string> get_tile(std::string_view file, int z, std::uint32_t x,
                                           std::uint32_t y) {
  const std::uint64_t id = zxy_to_tile_id(z, x, y);
  const Header h = read_header(file);
  std::vector<Entry> directory = decode_directory(file.substr(h.root_dir_offset, h.root_dir_length),
                                                  h.internal_compression, "root directory");
  for (int depth = 0; depth <= kMaxDirectoryDepth; ++depth) {
    auto after = std::upper_bound(directory.begin(), directory.end(), id,
                                  [](std::uint64_t v, const Entry& e) { return v < e.tile_id; });
    if (after == directory.begin()) return std::nullopt;
    const Entry e = *(after - 1);
    if (e.run_length == 0) {
      directory = detail::read_leaf(file, h, e);
      continue;
    }
    if (id - e.tile_id >= e.run_length) return std::nullopt;
    detail::check_tile_inside_data(h, e);
    return std::string(file.substr(h.tile_data_offset + e.offset, e.length));
  }
  detail::fail("leaf directories nested deeper than " + std::to_string(kMaxDirectoryDepth) +
               " levels while looking up tile id " + std::to_string(id));
}

// Whole-archive check: everything read_all_entries checks, plus
//  * metadata decompresses;
//  * the header counts, when not 0 (= unknown), match the directories (spec
//    3.2): addressed tiles = sum of run lengths, tile entries = entries with
//    run length > 0, tile contents = number of distinct tile offsets;
//  * if clustered (spec 3.2 "Clustered"): in tile id order, the first tile is
//    at offset 0 and each tile starts either exactly where the data written so
//    far ends, or at a lesser offset (a deduplicated tile).
// Returns the expanded entries for further checks.
inline std::vector<Entry> validate_archive(std::string_view file) {
  using detail::fail;
  const Header h = read_header(file);
  read_metadata(file);
  std::vector<Entry> entries = read_all_entries(file);

  std::uint64_t addressed = 0;
  std::set<std::uint64_t> offsets;
  for (const Entry& e : entries) {
    addressed += e.run_length;
    offsets.insert(e.offset);
  }
  auto check_count = [](const char* name, int byte, std::uint64_t in_header, std::uint64_t actual) {
    if (in_header != 0 && in_header != actual) {
      fail(std::string("header ") + name + " (byte " + std::to_string(byte) + ") is " +
           std::to_string(in_header) + " but the directories give " + std::to_string(actual));
    }
  };
  check_count("number of addressed tiles", 72, h.addressed_tiles_count, addressed);
  check_count("number of tile entries", 80, h.tile_entries_count, entries.size());
  check_count("number of tile contents", 88, h.tile_contents_count, offsets.size());

  if (h.clustered) {
    std::uint64_t data_end = 0;  // end of the furthest tile data seen so far
    for (const Entry& e : entries) {
      if (e.offset == data_end) {
        data_end += e.length;
      } else if (e.offset > data_end) {
        fail("archive is marked clustered but tile id " + std::to_string(e.tile_id) +
             " starts at offset " + std::to_string(e.offset) + ", after the end " +
             std::to_string(data_end) + " of the previous tile data");
      }
    }
  }
  return entries;
}

}  // namespace spec_readers::pmtiles
