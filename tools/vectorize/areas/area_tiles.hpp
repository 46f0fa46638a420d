// Passes 2 and 3 of an area build (areas_builder.hpp): each feature's
// polygons (valid, in the tiling CRS, from the scratch file pass 1 wrote)
// are, per zoom, snapped to the zoom's grid (area_geometry.hpp), repaired
// where snapping broke them, clipped to every tile they reach (plus the
// buffer) by GEOS and sorted by tile; then each tile is encoded (§12) and
// written in key order. Parallel work is done in batches consumed in order,
// so output is identical for any thread count.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "geo/geos_polygons.hpp"
#include "kit/progress.hpp"
#include "kit/scratch_file.hpp"
#include "tileformat/package.hpp"
#include "tileformat/tiling.hpp"
#include "tiles/tile_sorter.hpp"

namespace globe {

// One feature of pass 1: its polygons in the tiling CRS.
struct AreaFeature {
  uint64_t id = 0;
  uint32_t class_id = 0;
  PlaneMultiPolygon polygons;
};

// Pass 1's output, read back in order by the cut pass.
class AreaScratch {
 public:
  explicit AreaScratch(std::string path) : file_(std::move(path)) {}
  void write(const AreaFeature& f);
  void rewind() { file_.rewind(); }
  bool read(AreaFeature& f);

 private:
  ScratchFile file_;
  std::vector<uint8_t> buffer_;
};

struct AreaTileOptions {
  tileformat::Tiling tiling;
  tileformat::Bounds area;  // tiling CRS: the part to keep
  int min_zoom = 0, max_zoom = 0;
  int extent = 4096;
  int buffer = 64;           // units past each tile edge
  double simplify_px = 0.5;  // the snapping grid of a zoom, in pixels of a 256 px tile
  int threads = 1;
  // The class of feature `id` (a choropleth's, known after reading); none:
  // the class the feature was written with.
  std::function<uint32_t(uint64_t id)> class_of;
  // Zooms to cut a feature at (bit z; a shard's); none: every zoom.
  std::function<uint32_t(const AreaFeature&)> zooms;
  // Tiles to keep (a shard's); none: every tile.
  std::function<bool(tileformat::TileId)> keeps;
};

struct AreaTileStats {
  uint64_t polygons = 0, vertices = 0;  // written, all zooms
  uint64_t max_zoom_vertices = 0;       // written at the finest zoom
  uint64_t dropped_small = 0;           // polygons below a zoom's grid, left out there
  uint64_t resnapped = 0;               // tile pieces GEOS repaired after snapping
};

// The snapping step of zoom z in tile units (1 at the finest zoom).
double area_snap_step(const AreaTileOptions& o, int z);

void cut_area_tiles(AreaScratch& scratch, uint64_t features, const AreaTileOptions& o,
                    TileSorter& sorter, AreaTileStats& stats, Progress& progress);

// Encodes the sorted tiles and puts them in `writer` (a resumed package's
// tiles, which come first in key order, are skipped).
void encode_area_tiles(TileSorter& sorter, const AreaTileOptions& o,
                       tileformat::PackageWriter& writer, AreaTileStats& stats, Progress& progress);

}  // namespace globe
