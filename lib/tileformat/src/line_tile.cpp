// Line-cluster tile codec (docs/tileformat.md §7).
#include "tileformat/line_tile.hpp"

#include <algorithm>
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

struct Header {
  uint32_t extent, grid, reach, features, runs, segments, points, cell_entries, raw_size,
      compressed_size;
};

[[noreturn]] void fail(const std::string& section, const std::string& msg) {
  throw FormatError(section, "line tile: " + msg);
}

// §7.1 invariants that need no payload; also bounds what decoding allocates.
void check_header(const Header& h) {
  if (h.extent < 16 || h.extent > kMaxExtent)
    fail("7.1",
         "extent " + std::to_string(h.extent) + " outside 16.." + std::to_string(kMaxExtent));
  if (h.grid < 1 || h.grid > kMaxGrid || h.extent % h.grid != 0)
    fail("7.1", "grid " + std::to_string(h.grid) + " must be 1.." + std::to_string(kMaxGrid) +
                    " and divide the extent " + std::to_string(h.extent));
  if (h.reach > h.extent) fail("7.1", "reach larger than the extent");
  if (h.raw_size > kMaxRawSize) fail("7.1", "payload larger than 256 MiB");
  // Every element takes at least this many payload bytes (§7.2).
  const uint64_t min_bytes = uint64_t{h.features} + 3ull * h.runs +
                             2ull * (uint64_t{h.segments} + h.runs) + 4ull * h.points +
                             uint64_t{h.grid} * h.grid + h.cell_entries;
  if (min_bytes > h.raw_size) fail("7.1", "counts do not fit the payload size");
}

Header read_header(ByteReader& r) {
  Header h{};
  for (uint32_t* f : {&h.extent, &h.grid, &h.reach, &h.features, &h.runs, &h.segments, &h.points,
                      &h.cell_entries, &h.raw_size, &h.compressed_size})
    *f = r.u32();
  check_header(h);
  return h;
}

uint32_t checked_u32(ByteReader& r, uint64_t below, const char* what) {
  const uint64_t v = r.varint();
  if (v >= below) r.fail(std::string(what) + " " + std::to_string(v) + " out of range");
  return static_cast<uint32_t>(v);
}

int32_t checked_coord(ByteReader& r, int64_t& prev, int64_t extent) {
  // prev is in range, so a valid delta is within 3 extents; checking it
  // first keeps the sum from overflowing (found by fuzz_line_tile).
  const int64_t delta = r.svarint();
  if (delta < -3 * extent || delta > 3 * extent)
    r.fail("vertex delta " + std::to_string(delta) + " reaches outside -extent..2*extent");
  prev += delta;
  if (prev < -extent || prev > 2 * extent)
    r.fail("vertex coordinate " + std::to_string(prev) + " outside -extent..2*extent");
  return static_cast<int32_t>(prev);
}

}  // namespace

uint32_t LineTile::segment_count() const {
  uint64_t n = 0;
  for (const LineRun& r : runs)
    n += r.vertex_count - 1;
  return static_cast<uint32_t>(n);
}

std::vector<LineSegment> LineTile::segments() const {
  std::vector<LineSegment> out;
  out.reserve(segment_count());
  for (const LineRun& r : runs)
    for (uint32_t i = 0; i + 1 < r.vertex_count; ++i)
      out.push_back(
          {vertices[r.first_vertex + i], vertices[r.first_vertex + i + 1], r.feature, r.class_id});
  return out;
}

uint32_t LineTile::cell_of(double x, double y) const {
  const double cs = double(extent) / grid;
  auto index = [&](double v) {
    return static_cast<uint32_t>(std::clamp(v / cs, 0.0, double(grid - 1)));
  };
  return index(y) * grid + index(x);
}

std::vector<uint8_t> encode_line_tile(const LineTile& t, int zstd_level) {
  ByteWriter p;  // §7.2 payload
  write_increasing_ids(p, t.feature_ids, "7.2", "line tile: feature");
  uint32_t next_vertex = 0;
  for (const LineRun& r : t.runs) {
    if (r.vertex_count < 2 || r.first_vertex != next_vertex || r.feature >= t.feature_ids.size())
      fail("7.2", "runs must have >= 2 vertices, follow each other and name a listed feature");
    next_vertex += r.vertex_count;
    p.varint(r.feature);
    p.varint(r.class_id);
    p.varint(r.vertex_count - 2);
  }
  if (next_vertex != t.vertices.size()) fail("7.2", "vertices not covered by runs");
  int64_t px = 0, py = 0;
  for (const LineVertex& v : t.vertices) {
    p.svarint(v.x - px);
    p.svarint(v.y - py);
    px = v.x;
    py = v.y;
  }
  px = py = 0;
  for (const LinePoint& pt : t.points) {
    if (pt.feature >= t.feature_ids.size()) fail("7.2", "point names an unlisted feature");
    p.varint(pt.feature);
    p.varint(pt.class_id);
    p.svarint(pt.at.x - px);
    p.svarint(pt.at.y - py);
    px = pt.at.x;
    py = pt.at.y;
  }
  const size_t cells = size_t{t.grid} * t.grid;
  if (t.cell_offsets.size() != cells + 1 || t.cell_offsets.back() != t.cell_segments.size())
    fail("7.3", "cluster grid not built (call build_cluster_grid)");
  write_cell_lists(p, t.cell_offsets, t.cell_segments);
  const std::vector<uint8_t> raw = p.take();
  const std::vector<uint8_t> packed = zstd_compress(raw, zstd_level);
  Header h{t.extent,
           t.grid,
           t.reach,
           static_cast<uint32_t>(t.feature_ids.size()),
           static_cast<uint32_t>(t.runs.size()),
           t.segment_count(),
           static_cast<uint32_t>(t.points.size()),
           static_cast<uint32_t>(t.cell_segments.size()),
           static_cast<uint32_t>(raw.size()),
           static_cast<uint32_t>(packed.size())};
  check_header(h);
  ByteWriter body;
  for (uint32_t f : {h.extent, h.grid, h.reach, h.features, h.runs, h.segments, h.points,
                     h.cell_entries, h.raw_size, h.compressed_size})
    body.u32(f);
  body.bytes(packed);
  return wrap_blob(BlobKind::kLineClusters, body.take());
}

LineTileCounts peek_line_tile_counts(std::span<const uint8_t> blob) {
  ByteReader r(read_blob_header(blob, BlobKind::kLineClusters), "line tile header", "7.1");
  const Header h = read_header(r);
  return {h.features, h.runs, h.segments, h.points, h.cell_entries};
}

LineTile decode_line_tile(std::span<const uint8_t> blob) {
  ByteReader hr(read_blob_header(blob, BlobKind::kLineClusters), "line tile header", "7.1");
  const Header h = read_header(hr);
  const auto raw =
      zstd_decompress(hr.bytes(h.compressed_size), h.raw_size, "line tile payload", "7.2");
  hr.expect_end();

  LineTile t;
  t.extent = h.extent;
  t.grid = h.grid;
  t.reach = h.reach;
  ByteReader r(raw, "line tile payload", "7.2");
  t.feature_ids = read_increasing_ids(r, h.features, "feature");
  t.runs.resize(h.runs);
  uint64_t vertex_total = 0;
  for (LineRun& run : t.runs) {
    run.feature = checked_u32(r, h.features, "run feature index");
    run.class_id = checked_u32(r, 1u << 16, "class id");
    run.first_vertex = static_cast<uint32_t>(vertex_total);
    run.vertex_count = checked_u32(r, uint64_t{h.segments} + 1, "run length") + 2;
    vertex_total += run.vertex_count;
  }
  if (vertex_total != uint64_t{h.segments} + h.runs)
    r.fail("runs hold " + std::to_string(vertex_total - h.runs) + " segments, header says " +
           std::to_string(h.segments));
  t.vertices.resize(vertex_total);
  const int64_t e = h.extent;
  int64_t px = 0, py = 0;
  for (LineVertex& v : t.vertices) {
    v.x = checked_coord(r, px, e);
    v.y = checked_coord(r, py, e);
  }
  t.points.resize(h.points);
  px = py = 0;
  for (LinePoint& pt : t.points) {
    pt.feature = checked_u32(r, h.features, "point feature index");
    pt.class_id = checked_u32(r, 1u << 16, "class id");
    pt.at.x = checked_coord(r, px, e);
    pt.at.y = checked_coord(r, py, e);
  }
  r.set_section("7.3");
  read_cell_lists(r, size_t{h.grid} * h.grid, h.cell_entries, h.segments, "segment", t.cell_offsets,
                  t.cell_segments);
  r.expect_end();
  return t;
}

}  // namespace tileformat
