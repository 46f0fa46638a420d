// Reading PMTiles v3 headers and directories (see pmtiles_read.hpp).
#include "tileformat/pmtiles_read.hpp"

#include <algorithm>
#include <cstring>
#include <string>

namespace tileformat::pmtiles {
namespace {

uint64_t le(std::span<const uint8_t> b, size_t at, int n) {
  uint64_t v = 0;
  for (int i = n - 1; i >= 0; --i)
    v = (v << 8) | b[at + size_t(i)];
  return v;
}

double e7(std::span<const uint8_t> b, size_t at) {
  return double(int32_t(uint32_t(le(b, at, 4)))) / 1e7;
}

struct Varints {
  std::span<const uint8_t> b;
  size_t at = 0;
  uint64_t next() {
    uint64_t v = 0;
    for (int shift = 0; shift < 64; shift += 7) {
      if (at >= b.size()) throw PmtilesError("PMTiles directory: truncated varint");
      const uint8_t byte = b[at++];
      v |= uint64_t(byte & 0x7f) << shift;
      if (!(byte & 0x80)) return v;
    }
    throw PmtilesError("PMTiles directory: varint longer than 10 bytes");
  }
};

}  // namespace

Header decode_header(std::span<const uint8_t> b) {
  if (b.size() < kHeaderSize) throw PmtilesError("PMTiles: fewer than 127 bytes of header");
  if (std::memcmp(b.data(), "PMTiles", 7) != 0) throw PmtilesError("not a PMTiles archive");
  if (b[7] != 3) throw PmtilesError("PMTiles version " + std::to_string(b[7]) + ", not 3");
  Header h;
  uint64_t* fields[] = {&h.root_offset,     &h.root_length,  &h.metadata_offset, &h.metadata_length,
                        &h.leaf_offset,     &h.leaf_length,  &h.data_offset,     &h.data_length,
                        &h.addressed_tiles, &h.tile_entries, &h.tile_contents};
  for (size_t i = 0; i < std::size(fields); ++i)
    *fields[i] = le(b, 8 + 8 * i, 8);
  h.clustered = b[96] != 0;
  h.internal_compression = Compression(b[97]);
  h.info.tile_compression = Compression(b[98]);
  h.info.tile_type = TileType(b[99]);
  h.info.min_zoom = b[100];
  h.info.max_zoom = b[101];
  h.info.min_lon = e7(b, 102);
  h.info.min_lat = e7(b, 106);
  h.info.max_lon = e7(b, 110);
  h.info.max_lat = e7(b, 114);
  h.info.center_zoom = b[118];
  h.info.center_lon = e7(b, 119);
  h.info.center_lat = e7(b, 123);
  if (h.info.min_zoom > h.info.max_zoom || h.info.max_zoom > 31)
    throw PmtilesError("PMTiles header: zooms " + std::to_string(h.info.min_zoom) + ".." +
                       std::to_string(h.info.max_zoom));
  return h;
}

std::vector<Entry> decode_directory(std::span<const uint8_t> bytes) {
  Varints in{bytes};
  const uint64_t n = in.next();
  if (n > bytes.size()) throw PmtilesError("PMTiles directory: more entries than bytes");
  std::vector<Entry> out(static_cast<size_t>(n));
  uint64_t id = 0;
  for (Entry& e : out) {
    const uint64_t delta = in.next();
    if (delta > ~uint64_t{0} - id) throw PmtilesError("PMTiles directory: tile ids overflow");
    e.tile_id = id += delta;
  }
  for (Entry& e : out) {
    const uint64_t r = in.next();
    if (r > UINT32_MAX) throw PmtilesError("PMTiles directory: run length too large");
    e.run_length = uint32_t(r);
  }
  for (Entry& e : out) {
    const uint64_t l = in.next();
    if (l > UINT32_MAX) throw PmtilesError("PMTiles directory: entry length too large");
    e.length = uint32_t(l);
  }
  for (size_t i = 0; i < out.size(); ++i) {
    const uint64_t v = in.next();
    if (v == 0) {
      if (i == 0) throw PmtilesError("PMTiles directory: the first offset is relative");
      out[i].offset = out[i - 1].offset + out[i - 1].length;
    } else {
      out[i].offset = v - 1;
    }
  }
  return out;
}

const Entry* find_entry(const std::vector<Entry>& entries, uint64_t tile_id) {
  auto it = std::upper_bound(entries.begin(), entries.end(), tile_id,
                             [](uint64_t id, const Entry& e) { return id < e.tile_id; });
  if (it == entries.begin()) return nullptr;
  const Entry& e = *(it - 1);
  if (e.run_length == 0) return &e;  // a leaf directory
  if (tile_id - e.tile_id < e.run_length) return &e;
  return nullptr;
}

}  // namespace tileformat::pmtiles
