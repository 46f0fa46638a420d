// Area tiles (format §12) on their way from a package to the GPU, within a
// memory budget (data/arena_tile_cache.hpp does the caching), each decoded on
// the loader thread into the words the fill pass reads per pixel
// (docs/viewer.md "Areas"):
//
// A C x C grid of cells over the tile; per cell the polygons that matter
// there, each with its winding number at the cell's reference point (a fixed
// non-integer offset from the cell's top-left corner, so no vertex or
// integer-aligned edge passes through it) and the polygon's edges that touch
// the cell. A pixel's winding number for a polygon is the reference point's
// plus the signed crossings of the segment from the reference point to the
// pixel by those edges: exact at any zoom and across tile borders, with no
// geometry draped on the terrain.
//
// Words (u32): cell offsets (C*C + 1, into the entries), entries (4 words:
// polygon, winding as int bits, first edge reference, edge references), edge
// references (edge indices), edges (5 words: ax, ay, bx, by as float bits,
// tile units, then 1 where the edge is not outlined), polygons (2 words: class
// id, feature index).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "data/arena_tile_cache.hpp"
#include "runtime/area_package.hpp"
#include "tileformat/area_tile.hpp"

namespace globe::viewer {

inline constexpr uint32_t kAreaEntryWords = 4, kAreaEdgeWords = 5, kAreaPolygonWords = 2;
// The cells' reference point, in tile units from their top-left corner.
inline constexpr double kAreaRefX = 0.41421356, kAreaRefY = 0.73205081;

struct DecodedAreaTile {
  uint32_t extent = 0, grid = 0;
  uint32_t entries = 0, edge_refs = 0, edges = 0, polygons = 0;
  std::vector<uint64_t> feature_ids;      // by feature index (kept for picking)
  std::vector<uint32_t> polygon_feature;  // by polygon (kept for picking)
  std::vector<uint32_t> words;
  // Word offsets of the sections.
  uint32_t entries_at() const { return grid * grid + 1; }
  uint32_t edge_refs_at() const { return entries_at() + entries * kAreaEntryWords; }
  uint32_t edges_at() const { return edge_refs_at() + edge_refs; }
  uint32_t polygons_at() const { return edges_at() + edges * kAreaEdgeWords; }
};

// The fill pass's words of a decoded tile with a grid of `grid` cells a side;
// a cell lists the edges that pass within `reach` units of it (outlines near
// its sides are drawn whole). Edges along `world_sides` (map_edge_sides)
// are where polygons were cut at the map's edge, not borders: they fill but
// are not outlined. Exposed for tests.
DecodedAreaTile area_tile_words(const tileformat::AreaTile& tile, uint32_t grid = 32,
                                double reach = 24, uint32_t world_sides = 0);

// The winding number at tile point (x, y) of polygon `polygon` by the words
// alone, as the shader computes it (for tests).
int area_words_winding(const DecodedAreaTile& d, uint32_t polygon, double x, double y);

using AreaRecord = ArenaRecord<DecodedAreaTile>;

class AreaCache final : public ArenaTileCache<DecodedAreaTile> {
 public:
  AreaCache(const std::string& path, AreaPackage package, uint64_t budget_bytes);
  ~AreaCache() override;
  const AreaPackage& package() const { return package_; }

 private:
  AreaPackage package_;
};

}  // namespace globe::viewer
