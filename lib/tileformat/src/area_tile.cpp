// Area tile codec (docs/tileformat.md §12).
#include "tileformat/area_tile.hpp"

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

struct Header {
  uint32_t extent, buffer, features, polygons, rings, vertices, raw_size, compressed_size;
};

[[noreturn]] void fail(const std::string& section, const std::string& msg) {
  throw FormatError(section, "area tile: " + msg);
}

// §12.1 invariants that need no payload; also bounds what decoding allocates.
void check_header(const Header& h) {
  if (h.extent < 16 || h.extent > kMaxExtent)
    fail("12.1",
         "extent " + std::to_string(h.extent) + " outside 16.." + std::to_string(kMaxExtent));
  if (h.buffer > h.extent) fail("12.1", "buffer larger than the extent");
  if (h.raw_size > kMaxRawSize) fail("12.1", "payload larger than 256 MiB");
  if (h.features > h.polygons) fail("12.1", "more features than polygons");
  if (h.polygons > h.rings) fail("12.1", "more polygons than rings");
  if (uint64_t{h.rings} * 3 > h.vertices) fail("12.1", "fewer than 3 vertices a ring");
  // Every element takes at least this many payload bytes (§12.2).
  const uint64_t min_bytes = uint64_t{h.features} + 3ull * h.polygons + h.rings + 2ull * h.vertices;
  if (min_bytes > h.raw_size) fail("12.1", "counts do not fit the payload size");
}

Header read_header(ByteReader& r) {
  Header h{};
  for (uint32_t* f : {&h.extent, &h.buffer, &h.features, &h.polygons, &h.rings, &h.vertices,
                      &h.raw_size, &h.compressed_size})
    *f = r.u32();
  check_header(h);
  return h;
}

// The orientation rule of §12.2: exterior rings positive, holes negative.
void check_orientation(const AreaTile& t, const std::vector<uint32_t>& offsets,
                       const std::string& section) {
  for (size_t p = 0; p < t.polygons.size(); ++p) {
    const AreaPolygon& poly = t.polygons[p];
    for (uint32_t k = 0; k < poly.ring_count; ++k) {
      const uint32_t r = poly.first_ring + k;
      const int64_t a = ring_area2({t.vertices.data() + offsets[r], t.ring_sizes[r]});
      if (k == 0 ? a <= 0 : a >= 0)
        fail(section, "polygon " + std::to_string(p) + (k == 0 ? ": exterior ring" : ": hole") +
                          " winds the wrong way (or has no area)");
    }
  }
}

}  // namespace

std::vector<uint32_t> AreaTile::ring_offsets() const {
  std::vector<uint32_t> o(ring_sizes.size() + 1, 0);
  for (size_t r = 0; r < ring_sizes.size(); ++r)
    o[r + 1] = o[r] + ring_sizes[r];
  return o;
}

int64_t ring_area2(std::span<const LineVertex> ring) {
  int64_t a = 0;
  for (size_t i = 0, n = ring.size(); i < n; ++i) {
    const LineVertex& p = ring[i];
    const LineVertex& q = ring[(i + 1) % n];
    a += int64_t{p.x} * q.y - int64_t{q.x} * p.y;
  }
  return a;
}

uint32_t map_edge_sides(const Tiling& t, TileId id) {
  if (t.scheme == Scheme::kLocal) return 0;
  uint32_t sides = 0;
  if (id.x == 0) sides |= kMapEdgeLeft;
  if (id.x + 1 == t.tiles_x(id.z)) sides |= kMapEdgeRight;
  if (id.y == 0) sides |= kMapEdgeTop;
  if (id.y + 1 == t.tiles_y(id.z)) sides |= kMapEdgeBottom;
  return sides;
}

bool along_map_edge(uint32_t sides, double ax, double ay, double bx, double by, double size) {
  return ((sides & kMapEdgeLeft) && ax == 0 && bx == 0) ||
         ((sides & kMapEdgeRight) && ax == size && bx == size) ||
         ((sides & kMapEdgeTop) && ay == 0 && by == 0) ||
         ((sides & kMapEdgeBottom) && ay == size && by == size);
}

std::vector<uint8_t> encode_area_tile(const AreaTile& t, int zstd_level) {
  const std::vector<uint32_t> offsets = t.ring_offsets();
  if (offsets.back() != t.vertices.size()) fail("12.2", "ring sizes do not add up to the vertices");
  uint32_t next_ring = 0, last_feature = 0;
  for (const AreaPolygon& p : t.polygons) {
    if (p.feature >= t.feature_ids.size()) fail("12.2", "polygon of a feature not in the tile");
    if (p.feature < last_feature) fail("12.2", "polygons not in feature order");
    if (p.first_ring != next_ring || p.ring_count < 1)
      fail("12.2", "polygons must own consecutive rings, at least one each");
    last_feature = p.feature;
    next_ring += p.ring_count;
  }
  if (next_ring != t.ring_sizes.size()) fail("12.2", "rings not owned by a polygon");
  for (uint32_t s : t.ring_sizes)
    if (s < 3) fail("12.2", "a ring of fewer than 3 vertices");
  const int64_t lo = -int64_t{t.buffer}, hi = int64_t{t.extent} + t.buffer;
  for (const LineVertex& v : t.vertices)
    if (v.x < lo || v.x > hi || v.y < lo || v.y > hi)
      fail("12.2", "vertex outside the tile and its buffer");
  check_orientation(t, offsets, "12.2");

  ByteWriter p;  // §12.2 payload
  write_increasing_ids(p, t.feature_ids, "12.2", "area tile: feature");
  uint32_t prev = 0;
  for (const AreaPolygon& poly : t.polygons) {
    p.varint(poly.feature - prev);  // feature indices never decrease
    prev = poly.feature;
    p.varint(poly.class_id);
    p.varint(poly.ring_count - 1);
  }
  for (uint32_t s : t.ring_sizes)
    p.varint(s - 3);
  int64_t px = 0, py = 0;
  for (const LineVertex& v : t.vertices) {
    p.svarint(v.x - px);
    p.svarint(v.y - py);
    px = v.x;
    py = v.y;
  }
  const std::vector<uint8_t> raw = p.take();
  const std::vector<uint8_t> packed = zstd_compress(raw, zstd_level);
  const Header h{t.extent,
                 t.buffer,
                 static_cast<uint32_t>(t.feature_ids.size()),
                 static_cast<uint32_t>(t.polygons.size()),
                 static_cast<uint32_t>(t.ring_sizes.size()),
                 static_cast<uint32_t>(t.vertices.size()),
                 static_cast<uint32_t>(raw.size()),
                 static_cast<uint32_t>(packed.size())};
  check_header(h);
  ByteWriter body;
  for (uint32_t f : {h.extent, h.buffer, h.features, h.polygons, h.rings, h.vertices, h.raw_size,
                     h.compressed_size})
    body.u32(f);
  body.bytes(packed);
  return wrap_blob(BlobKind::kAreas, body.take());
}

AreaTileCounts peek_area_tile_counts(std::span<const uint8_t> blob) {
  ByteReader r(read_blob_header(blob, BlobKind::kAreas), "area tile header", "12.1");
  const Header h = read_header(r);
  return {h.features, h.polygons, h.rings, h.vertices};
}

AreaTile decode_area_tile(std::span<const uint8_t> blob) {
  ByteReader hr(read_blob_header(blob, BlobKind::kAreas), "area tile header", "12.1");
  const Header h = read_header(hr);
  const auto raw =
      zstd_decompress(hr.bytes(h.compressed_size), h.raw_size, "area tile payload", "12.2");
  hr.expect_end();

  AreaTile t;
  t.extent = h.extent;
  t.buffer = h.buffer;
  ByteReader r(raw, "area tile payload", "12.2");
  t.feature_ids = read_increasing_ids(r, h.features, "feature");
  t.polygons.resize(h.polygons);
  uint64_t feature = 0, ring = 0;
  std::vector<bool> seen(h.features, false);
  for (AreaPolygon& p : t.polygons) {
    feature += r.varint();
    if (feature >= h.features) r.fail("polygon of a feature not in the tile");
    seen[feature] = true;
    p.feature = static_cast<uint32_t>(feature);
    const uint64_t c = r.varint();
    if (c > 0xffffffffu) r.fail("class out of range");
    p.class_id = static_cast<uint32_t>(c);
    const uint64_t rings = r.varint() + 1;
    if (rings > h.rings - ring) r.fail("more rings than the header says");
    p.first_ring = static_cast<uint32_t>(ring);
    p.ring_count = static_cast<uint32_t>(rings);
    ring += rings;
  }
  if (ring != h.rings) r.fail("rings not owned by a polygon");
  for (uint32_t f = 0; f < h.features; ++f)
    if (!seen[f]) r.fail("a feature without a polygon");
  t.ring_sizes.resize(h.rings);
  uint64_t vertices = 0;
  for (uint32_t& s : t.ring_sizes) {
    const uint64_t n = r.varint() + 3;
    if (n > h.vertices - vertices) r.fail("more vertices than the header says");
    s = static_cast<uint32_t>(n);
    vertices += n;
  }
  if (vertices != h.vertices) r.fail("ring sizes do not add up to the vertices");
  t.vertices.resize(h.vertices);
  const int64_t lo = -int64_t{h.buffer}, hi = int64_t{h.extent} + h.buffer, span = hi - lo;
  int64_t px = 0, py = 0;
  for (LineVertex& v : t.vertices) {
    // Deltas are checked before they are added (no overflow on hostile input).
    const int64_t dx = r.svarint(), dy = r.svarint();
    if (dx < -span || dx > span || dy < -span || dy > span)
      r.fail("vertex delta reaches outside the tile and its buffer");
    px += dx;
    py += dy;
    if (px < lo || py < lo || px > hi || py > hi)
      r.fail("vertex (" + std::to_string(px) + ", " + std::to_string(py) +
             ") outside the tile and its buffer");
    v = {static_cast<int32_t>(px), static_cast<int32_t>(py)};
  }
  r.expect_end();
  check_orientation(t, t.ring_offsets(), "12.2");
  return t;
}

}  // namespace tileformat
