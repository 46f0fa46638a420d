// Point tile codec (docs/tileformat.md §11).
#include "tileformat/point_tile.hpp"

#include <algorithm>
#include <bit>
#include <string>

#include "internal/cell_lists.hpp"
#include "tileformat/blob_header.hpp"
#include "tileformat/byte_io.hpp"
#include "tileformat/error.hpp"
#include "tileformat/zstd_codec.hpp"

namespace tileformat {
namespace {

constexpr uint32_t kMaxRawSize = 256u << 20;
constexpr uint32_t kMaxExtent = 1u << 24;
constexpr uint32_t kMaxGrid = 1024;
constexpr uint32_t kMaxFields = 64;

struct Header {
  uint32_t extent, grid, reach, fields, places, cell_entries, raw_size, compressed_size;
};

[[noreturn]] void fail(const std::string& section, const std::string& msg) {
  throw FormatError(section, "point tile: " + msg);
}

// §11.1 invariants that need no payload; also bounds what decoding allocates.
void check_header(const Header& h) {
  if (h.extent < 16 || h.extent > kMaxExtent)
    fail("11.1",
         "extent " + std::to_string(h.extent) + " outside 16.." + std::to_string(kMaxExtent));
  if (h.grid < 1 || h.grid > kMaxGrid || h.extent % h.grid != 0)
    fail("11.1", "grid " + std::to_string(h.grid) + " must be 1.." + std::to_string(kMaxGrid) +
                     " and divide the extent " + std::to_string(h.extent));
  if (h.reach > h.extent) fail("11.1", "reach larger than the extent");
  if (h.fields < 1 || h.fields > kMaxFields)
    fail("11.1",
         std::to_string(h.fields) + " fields; 1.." + std::to_string(kMaxFields) + " allowed");
  if (h.raw_size > kMaxRawSize) fail("11.1", "payload larger than 256 MiB");
  // Every element takes at least this many payload bytes (§11.2).
  const uint64_t min_bytes =
      uint64_t{h.places} * (4 + 4ull * h.fields) + uint64_t{h.grid} * h.grid + h.cell_entries;
  if (min_bytes > h.raw_size) fail("11.1", "counts do not fit the payload size");
}

Header read_header(ByteReader& r) {
  Header h{};
  for (uint32_t* f : {&h.extent, &h.grid, &h.reach, &h.fields, &h.places, &h.cell_entries,
                      &h.raw_size, &h.compressed_size})
    *f = r.u32();
  check_header(h);
  return h;
}

}  // namespace

uint32_t PointTile::cell_of(double x, double y) const {
  const double cs = double(extent) / grid;
  auto index = [&](double v) {
    return static_cast<uint32_t>(std::clamp(v / cs, 0.0, double(grid - 1)));
  };
  return index(y) * grid + index(x);
}

void build_point_grid(PointTile& t) {
  const size_t cells = size_t{t.grid} * t.grid;
  std::vector<uint32_t> counts(cells, 0);
  for (const Place& p : t.places)
    for_each_cell_near(t, p.at, [&](uint32_t c) { ++counts[c]; });
  t.cell_offsets.assign(cells + 1, 0);
  for (size_t c = 0; c < cells; ++c)
    t.cell_offsets[c + 1] = t.cell_offsets[c] + counts[c];
  t.cell_places.assign(t.cell_offsets[cells], 0);
  std::vector<uint32_t> next(t.cell_offsets.begin(), t.cell_offsets.end() - 1);
  for (uint32_t i = 0; i < t.places.size(); ++i)
    for_each_cell_near(t, t.places[i].at, [&](uint32_t c) { t.cell_places[next[c]++] = i; });
}

std::vector<uint8_t> encode_point_tile(const PointTile& t, int zstd_level) {
  if (t.values.size() != t.places.size() * t.fields)
    fail("11.2", "values do not match places x fields");
  ByteWriter p;  // §11.2 payload
  std::vector<uint64_t> ids(t.places.size());
  for (size_t i = 0; i < ids.size(); ++i)
    ids[i] = t.places[i].id;
  write_increasing_ids(p, ids, "11.2", "point tile: place");
  for (const Place& pl : t.places) {
    if (pl.count < 1) fail("11.2", "a place stands for at least one source place");
    p.varint(pl.count - 1);
  }
  int64_t px = 0, py = 0;
  for (const Place& pl : t.places) {
    if (pl.at.x < 0 || pl.at.y < 0 || uint32_t(pl.at.x) > t.extent || uint32_t(pl.at.y) > t.extent)
      fail("11.2", "place outside 0..extent");
    p.svarint(pl.at.x - px);
    p.svarint(pl.at.y - py);
    px = pl.at.x;
    py = pl.at.y;
  }
  for (uint32_t f = 0; f < t.fields; ++f)
    for (size_t i = 0; i < t.places.size(); ++i)
      p.u32(std::bit_cast<uint32_t>(t.value(i, f)));
  const size_t cells = size_t{t.grid} * t.grid;
  if (t.cell_offsets.size() != cells + 1 || t.cell_offsets.back() != t.cell_places.size())
    fail("11.3", "cluster grid not built (call build_point_grid)");
  write_cell_lists(p, t.cell_offsets, t.cell_places);
  const std::vector<uint8_t> raw = p.take();
  const std::vector<uint8_t> packed = zstd_compress(raw, zstd_level);
  const Header h{t.extent,
                 t.grid,
                 t.reach,
                 t.fields,
                 static_cast<uint32_t>(t.places.size()),
                 static_cast<uint32_t>(t.cell_places.size()),
                 static_cast<uint32_t>(raw.size()),
                 static_cast<uint32_t>(packed.size())};
  check_header(h);
  ByteWriter body;
  for (uint32_t f : {h.extent, h.grid, h.reach, h.fields, h.places, h.cell_entries, h.raw_size,
                     h.compressed_size})
    body.u32(f);
  body.bytes(packed);
  return wrap_blob(BlobKind::kPoints, body.take());
}

PointTileCounts peek_point_tile_counts(std::span<const uint8_t> blob) {
  ByteReader r(read_blob_header(blob, BlobKind::kPoints), "point tile header", "11.1");
  const Header h = read_header(r);
  return {h.places, h.fields, h.cell_entries};
}

PointTile decode_point_tile(std::span<const uint8_t> blob) {
  ByteReader hr(read_blob_header(blob, BlobKind::kPoints), "point tile header", "11.1");
  const Header h = read_header(hr);
  const auto raw =
      zstd_decompress(hr.bytes(h.compressed_size), h.raw_size, "point tile payload", "11.2");
  hr.expect_end();

  PointTile t;
  t.extent = h.extent;
  t.grid = h.grid;
  t.reach = h.reach;
  t.fields = h.fields;
  ByteReader r(raw, "point tile payload", "11.2");
  t.places.resize(h.places);
  const std::vector<uint64_t> ids = read_increasing_ids(r, h.places, "place");
  for (uint32_t i = 0; i < h.places; ++i)
    t.places[i].id = ids[i];
  for (Place& pl : t.places) {
    const uint64_t c = r.varint();
    if (c >= 0xffffffffu) r.fail("place count out of range");
    pl.count = static_cast<uint32_t>(c + 1);
  }
  int64_t px = 0, py = 0;
  const int64_t e = h.extent;
  for (Place& pl : t.places) {
    // Deltas are checked before they are added (no overflow on hostile input).
    const int64_t dx = r.svarint(), dy = r.svarint();
    if (dx < -e || dx > e || dy < -e || dy > e) r.fail("place delta reaches outside 0..extent");
    px += dx;
    py += dy;
    if (px < 0 || py < 0 || px > e || py > e)
      r.fail("place (" + std::to_string(px) + ", " + std::to_string(py) + ") outside 0..extent");
    pl.at = {static_cast<int32_t>(px), static_cast<int32_t>(py)};
  }
  t.values.resize(size_t{h.places} * h.fields);
  for (uint32_t f = 0; f < h.fields; ++f)
    for (uint32_t i = 0; i < h.places; ++i)
      t.values[size_t{i} * h.fields + f] = std::bit_cast<float>(r.u32());
  r.set_section("11.3");
  read_cell_lists(r, size_t{h.grid} * h.grid, h.cell_entries, h.places, "place", t.cell_offsets,
                  t.cell_places);
  r.expect_end();
  return t;
}

}  // namespace tileformat
