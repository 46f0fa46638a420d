// BlockSynthesizer: terrain blocks made in the viewer, for sources that have
// heights but no MBlocks (raster-DEM tiles on foreign servers:
// raster_dem_reader.hpp). It turns each tile's grid of heights into the MBlock
// blob a terrain package would hold (docs/tileformat.md §5, §6) — quantized
// heights, the hole mask, the KPatch error tree — so that such a source goes
// through the same LOD (patch selection, screen-space error, crack-free
// edges) as a package. It reads nothing itself: the grids come from the
// caller's GridFn; the error trees from lib/runtime's error_tree.
//
// Not nested. A package's blocks are nested — a coarse block's sample
// equals the finer block's sample at the same spot — and the LOD relies on it
// where a patch drawn from zoom z meets one drawn from zoom z+1: they share
// those vertices. Heights a source resamples per zoom (a raster-DEM pyramid's
// pixel corners, a quantized-mesh pyramid's TINs) are not nested: 16-65 m
// apart on average at zooms 1-3 of etopo20's Terrarium tiles, up to 1-2 km.
// Forcing nesting (a block's samples at its parent's positions taken from
// the parent, up to zoom 0) was tried and dropped: the finest blocks then
// inherit the coarsest zooms' heights at a quarter, a sixteenth, ... of their
// samples — 11 km off on quantized-mesh (whose zoom 0 is good to 77 km). So
// the blocks keep their own samples, their metadata says so
// (globe:synthesized), and the renderer hangs skirts from such patches
// (TerrainRenderer::set_skirts), as CesiumJS does: no hole where two zooms
// meet, and every sample as the source has it.
//
// Error trees, and what they give up. A package's node errors measure a
// coarse block against the finest data under it (its child blocks). A remote
// source has no finer data at hand when a block is made, so every block's
// node errors are those of its own samples, the rule the tiler uses at its
// finest zoom (node_errors with no children). Coarser blocks may therefore
// understate their error against finer data: the LOD refines on the
// screen-space error of each block's own samples, and a detail that only the
// finer zooms show appears when the camera comes close enough for the finer
// blocks to be loaded anyway. It stays crack-free: the vertex errors of a
// block read the node errors of its 8 neighbours (docs/terrain.md "Error
// trees"), and an edge vertex is computed from the same neighbourhood in both
// blocks, from the same grids, so its error is the same in both; and the
// grids themselves must give neighbours the same edge samples (the GridFn's
// contract below).
//
// Holes (NaN) are filled as the tiler fills them (docs/terrain.md "Holes":
// corners without data at the fill height, edges linearly along the edge,
// the interior in waves inwards), from what both blocks of an edge see.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "data/fill_once_cache.hpp"
#include "tileformat/kpatch.hpp"
#include "tileformat/metadata.hpp"
#include "tileformat/tile_id.hpp"
#include "tileformat/tiling.hpp"

namespace globe::viewer {

class BlockSynthesizer {
 public:
  // Corner-registered samples of tile `id`: block_size * block_size heights
  // in metres, row-major from the north row, the tile's edges ON the
  // first/last rows/columns (so neighbours share their edge samples, which
  // must be equal in both); NaN = no data. nullopt = no tile there. May
  // throw (the exception passes through blob()). Called from several
  // threads at once.
  using GridFn = std::function<std::optional<std::vector<float>>(tileformat::TileId id)>;

  // block_size = 2^k + 1 with 2^k >= 2 * lattice; height_step > 0 (metres
  // per quantum; heights beyond +-kMaxQuantum quanta are clamped);
  // cached_blocks: how many tiles' quantized grids and node errors the LRU
  // keeps (at least 9 is useful: one neighbourhood). `tiling` says which
  // columns wrap at the antimeridian (tiles_x, wraps_x); rows at the poles
  // have no neighbour beyond. fill_height_m: the height of a block corner
  // without data. Throws std::invalid_argument for a bad size or lattice.
  BlockSynthesizer(int block_size, int lattice, double height_step, GridFn grid,
                   size_t cached_blocks,
                   tileformat::Tiling tiling = tileformat::Tiling::webmercator(),
                   double fill_height_m = 0.0);

  // The MBlock blob of `id`, or nullopt where grid() has no tile: heights
  // q = round(h / step), the hole mask, vertex errors over the 3 x 3
  // neighbourhood (a neighbour without a tile counts as absent). The same
  // inputs give the same bytes. Thread-safe; exceptions of grid() pass
  // through (nothing is cached for that tile then).
  std::optional<std::vector<uint8_t>> blob(tileformat::TileId id);
  // A floor under every node error of a block of zoom z, in metres (0: none):
  // what the source's coarser zooms are known to leave out — a
  // quantized-mesh level's geometric error, a raster-DEM zoom's pixel
  // spacing share — so the LOD refines where CesiumJS would, although a
  // block's own samples cannot say it. Set before the first blob().
  void set_level_error(std::function<double(int z)> metres);

  int block_size() const { return size_; }
  int lattice() const { return lattice_; }
  double height_step() const { return step_; }

 private:
  // One tile's quantized grid and its node errors (own samples only).
  struct Block {
    bool present = false;
    std::vector<int32_t> q;
    std::vector<uint8_t> valid;  // empty: all valid
    std::vector<uint32_t> node_errors;
  };
  std::shared_ptr<const Block> block(tileformat::TileId id);
  std::shared_ptr<const Block> make_block(tileformat::TileId id);
  std::optional<tileformat::TileId> neighbour(tileformat::TileId id, int dx, int dy) const;

  int size_, lattice_;
  double step_;
  GridFn grid_;
  std::function<double(int)> level_error_;
  tileformat::Tiling tiling_;
  int32_t fill_q_;
  tileformat::KPatchLayout layouts_[2];  // by TileId::diagonal()

  FillOnceCache<tileformat::TileId, Block> blocks_;
};

// CesiumJS's estimate of a terrain level's geometric error, in metres: the
// equator's length / 4 / (samples across a tile * tiles across at zoom 0) /
// 2^z (TerrainProvider.getEstimatedLevelZeroGeometricErrorForAHeightmap;
// quantized-mesh tiles: 65 samples; raster-DEM tiles: their pixels).
double cesium_level_error_m(int z, int samples_across, int roots_x);

// What the metadata of a synthesized web-mercator terrain says: the source
// (its URL as the package name), the blocks' shape and step, its zooms and
// lon/lat bounds (clamped to +-85.0511 degrees).
struct SynthesizedTerrain {
  std::string name;         // the source's URL
  std::string description;  // e.g. "Terrarium tiles from URL"
  int block_size = 257;
  int lattice = 16;
  double height_step = 0;
  double fill_height_m = 0;
  int min_zoom = 0, max_zoom = 0;
  tileformat::Bounds lonlat{-180, -tileformat::kWebMercatorMaxLat, 180,
                            tileformat::kWebMercatorMaxLat};
};

// The metadata map of a terrain package with these blocks
// (tileformat::to_metadata: format application/vnd.globe.mblock, tiling
// webmercator, globe:block_size, globe:kpatch_lattice, globe:height_step,
// minzoom/maxzoom, bounds, center), which open_terrain_package's reading
// (read_terrain_metadata) accepts.
// Also sets globe:synthesized = "1": blocks not nested (skirts wanted).
tileformat::MetadataMap terrain_metadata_for(const SynthesizedTerrain& t);

}  // namespace globe::viewer
