// Area tiles (docs/tileformat.md §12): the polygons of one quadtree tile,
// clipped to the tile widened by `buffer` units on every side, as rings of
// tile-local integer vertices (x east, y south, 0..extent across the tile).
// A polygon is one exterior ring and its holes; exterior rings wind
// clockwise as seen on screen (positive shoelace area with y down, MVT 2.1's
// convention), holes counter-clockwise. Rings are open: the first vertex is
// not repeated at the end.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "tileformat/line_tile.hpp"
#include "tileformat/tiling.hpp"

namespace tileformat {

struct AreaPolygon {
  uint32_t feature = 0;     // index into AreaTile::feature_ids
  uint32_t class_id = 0;    // style class (globe:classes) or choropleth class + 1 (0: no data)
  uint32_t first_ring = 0;  // into AreaTile::ring_sizes; that ring is the exterior
  uint32_t ring_count = 0;  // >= 1: the exterior, then the holes
};

struct AreaTile {
  uint32_t extent = 4096;             // units per tile edge
  uint32_t buffer = 64;               // units the polygons reach past each edge
  std::vector<uint64_t> feature_ids;  // strictly increasing ids of the features table
  std::vector<AreaPolygon> polygons;  // in feature order
  std::vector<uint32_t> ring_sizes;   // vertices of each ring, >= 3
  std::vector<LineVertex> vertices;   // every ring's vertices, ring after ring

  // Offset of ring r's first vertex in `vertices`.
  std::vector<uint32_t> ring_offsets() const;
};

// Counts readable from the uncompressed part of a blob (for `info`).
struct AreaTileCounts {
  uint32_t features = 0, polygons = 0, rings = 0, vertices = 0;
};

// Twice the signed area of a ring (shoelace, tile units, y down): positive
// for an exterior ring, negative for a hole.
int64_t ring_area2(std::span<const LineVertex> ring);

// Where polygons were cut rather than bordered: the sides of tile `id` that
// lie on a global tiling's own edge (the antimeridian left of the first
// column and right of the last, the poles' rows), as bits; none in a local
// tiling. Drawers leave edges along them unoutlined.
enum MapEdgeSide : uint32_t {
  kMapEdgeLeft = 1,
  kMapEdgeRight = 2,
  kMapEdgeTop = 4,
  kMapEdgeBottom = 8
};
uint32_t map_edge_sides(const Tiling& tiling, TileId id);
// Whether the edge a-b (tile units, or pixels: `size` units a tile side) runs
// along one of `sides`.
bool along_map_edge(uint32_t sides, double ax, double ay, double bx, double by, double size);

// Encodes `tile` as a blob with header. Throws FormatError if it breaks the
// §12 invariants (orientation included).
std::vector<uint8_t> encode_area_tile(const AreaTile& tile, int zstd_level = 9);
// Decodes and checks every §12 invariant; throws FormatError.
AreaTile decode_area_tile(std::span<const uint8_t> blob);
AreaTileCounts peek_area_tile_counts(std::span<const uint8_t> blob);

}  // namespace tileformat
