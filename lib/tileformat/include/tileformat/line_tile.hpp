// Line-cluster tiles (docs/tileformat.md §7): the clustered line buffer of one
// quadtree tile. Lines are stored as runs of tile-local integer vertices
// (x east, y south, 0..extent across the tile); consecutive vertices of a run
// form the tile's segments, numbered run after run. A C x C cluster grid in
// CSR form lists, per cell, every segment whose footprint (the segment
// widened by `reach` units) touches the cell. Points are stored unclustered.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace tileformat {

struct LineVertex {
  int32_t x = 0, y = 0;
  bool operator==(const LineVertex&) const = default;
};

struct LineRun {
  uint32_t feature = 0;       // index into LineTile::feature_ids
  uint32_t class_id = 0;      // style class (metadata globe:classes)
  uint32_t first_vertex = 0;  // into LineTile::vertices
  uint32_t vertex_count = 0;  // >= 2
};

struct LinePoint {
  uint32_t feature = 0, class_id = 0;
  LineVertex at;
};

struct LineSegment {
  LineVertex a, b;
  uint32_t feature = 0, class_id = 0;
};

struct LineTile {
  uint32_t extent = 4096;             // units per tile edge
  uint32_t grid = 32;                 // cluster cells per side; extent % grid == 0
  uint32_t reach = 0;                 // half-width in units the grid was built for
  std::vector<uint64_t> feature_ids;  // strictly increasing ids of the features table
  std::vector<LineRun> runs;
  std::vector<LineVertex> vertices;
  std::vector<LinePoint> points;
  std::vector<uint32_t> cell_offsets;   // grid*grid + 1, row-major cells (y, then x)
  std::vector<uint32_t> cell_segments;  // ascending segment indices per cell

  uint32_t segment_count() const;
  // All segments in index order, with their run's feature and class.
  std::vector<LineSegment> segments() const;
  // Cell of a tile-local position (clamped into the grid).
  uint32_t cell_of(double x, double y) const;
};

// Counts readable from the uncompressed part of a blob (for `info`).
struct LineTileCounts {
  uint32_t features = 0, runs = 0, segments = 0, points = 0, cell_entries = 0;
};

// Encodes `tile` (grid included; see build_cluster_grid) as a blob with
// header. Throws FormatError if the tile breaks the §7 invariants.
std::vector<uint8_t> encode_line_tile(const LineTile& tile, int zstd_level = 9);
// Decodes and checks every §7 invariant; throws FormatError.
LineTile decode_line_tile(std::span<const uint8_t> blob);
LineTileCounts peek_line_tile_counts(std::span<const uint8_t> blob);

}  // namespace tileformat
