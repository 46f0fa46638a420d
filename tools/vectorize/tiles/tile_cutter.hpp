// Cuts one projected feature into the tiles of one zoom (docs/lines.md
// "Pipeline"): each part is simplified (Douglas-Peucker at a fraction of a
// pixel of that zoom), each segment is clipped to every tile box it touches
// (the tile widened by the zoom's reach, so lines continue seamlessly across
// tile borders), and the pieces are snapped to the zoom's global integer grid
// (`extent` units per tile). Consecutive segments in one tile stay one run.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "lines/line_geometry.hpp"
#include "tileformat/line_tile.hpp"
#include "tileformat/tiling.hpp"

namespace globe {

// What one feature contributes to one tile: a run of a line, or a point.
struct TilePiece {
  bool point = false;
  uint32_t class_id = 0;
  std::vector<tileformat::LineVertex> vertices;  // tile-local units; 1 for a point

  std::vector<uint8_t> to_bytes() const;
  static TilePiece from_bytes(std::span<const uint8_t> bytes);
};

struct Emission {
  uint64_t key;  // tile_key()
  uint32_t sub;  // order within the feature
  TilePiece piece;
};

// Sort key of a tile: zoom, then row, then column.
uint64_t tile_key(tileformat::TileId id);
tileformat::TileId key_tile(uint64_t key);

struct ProjectedFeature {
  uint64_t id = 0;
  uint32_t class_id = 0;
  uint32_t zooms = ~0u;                // the zooms it is drawn at (bit z)
  std::vector<std::vector<XY>> lines;  // tiling CRS
  std::vector<XY> points;
};

struct CutStats {
  uint64_t runs = 0, segments = 0, collapsed_runs = 0, points = 0;
};

// What the cutter does with a run that snaps to a single grid point.
enum class Collapsed { kDrop, kKeep };

class TileCutter {
 public:
  // `area`: the part of the tiling CRS to keep (the scheme's extent, or --bbox).
  TileCutter(const tileformat::Tiling& tiling, int extent, double simplify_px,
             const tileformat::Bounds& area);

  // Appends f's pieces at zoom z; `reach_units` widens each tile's box.
  // `sub` numbers the pieces across calls for one feature. A run that
  // snaps to a single grid point is dropped (it is below the zoom's
  // resolution) unless Collapsed::kKeep: then it stays as a zero-length
  // segment, drawn as a dot, so the finest zoom loses no feature.
  void cut(const ProjectedFeature& f, int z, double reach_units, Collapsed collapsed, uint32_t& sub,
           std::vector<Emission>& out, CutStats& stats) const;

 private:
  void cut_part(std::span<const XY> part, uint32_t class_id, int z, double reach_units,
                Collapsed collapsed, uint32_t& sub, std::vector<Emission>& out,
                CutStats& stats) const;
  const tileformat::Tiling& tiling_;
  int extent_;
  double simplify_px_;
  tileformat::Bounds area_;
};

}  // namespace globe
