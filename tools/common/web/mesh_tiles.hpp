// A terrain package's tiles as quantized-mesh (docs/web.md "Quantized-mesh"),
// for the export and the server: each tile's samples from its block (zooms
// below the package's coarsest: every 2^k-th sample of that zoom's blocks,
// 0 m where it has none), cut into a TIN within CesiumJS's geometric error
// for the level (terrain_mesh.hpp; each tile alone, from the blocks of it
// and its eight neighbours), vertex normals from the samples around each
// vertex, and layer.json with the tiles' availability.
//
// Tile ids are the package's own (rows from the north); Cesium's rows count
// from the south (TMS), which the outputs and layer.json apply.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "runtime/terrain_package.hpp"
#include "tileformat/tile_id.hpp"
#include "web/lru_cache.hpp"
#include "web/terrain_mesh.hpp"
#include "web/terrain_sampler.hpp"

namespace globe::web {

// Each tile's own triangle errors (terrain_mesh.hpp), shared by the threads
// cutting one package's tiles.
using OwnErrorCache = LruCache<uint64_t, std::vector<float>>;

// Samples of one package for mesh tiles: one per thread (cheap to make), all
// sharing the package's decoded blocks and own errors.
class MeshTileSource {
 public:
  MeshTileSource(TerrainBlocks& blocks, OwnErrorCache& own_errors);

  // The tile's samples with a one-sample apron: NaN beyond the poles and,
  // from zoom 1 on at the package's zooms, where no block is; 0 m elsewhere
  // without a block.
  TileGrid grid(tileformat::TileId id);
  // The height at global sample (gx, gy) of zoom z (gx wraps around the
  // Earth); nullopt where no block has it.
  std::optional<double> sample(int z, int64_t gx, int64_t gy);
  // Whether the tile has samples: at zoom 0 and below the package's zooms
  // every tile of the Earth, elsewhere those with a block.
  bool has_tile(tileformat::TileId id);
  // The tile's saturated errors, from its own and its eight neighbours' own
  // errors (each computed once while the cache keeps it), for cutting the
  // tile at `threshold` only (own_errors' limit: they decide that cut as the
  // exact errors would). The threshold must be the same for every tile of a
  // zoom that shares the cache.
  MeshErrors errors(tileformat::TileId id, double threshold);
  const TerrainPackage& package() const { return package_; }

 private:
  // nullptr: no such tile.
  std::shared_ptr<const std::vector<float>> own(tileformat::TileId id, double limit);

  TerrainPackage& package_;
  TerrainSampler sampler_;
  OwnErrorCache& own_errors_;
};

struct MeshTileOptions {
  double error_scale = 1.0;  // threshold = scale * cesium_level_error(z)
  // At the finest zoom (CesiumJS cannot refine past it, so it shows those
  // tiles however close the camera comes): metres, the data's own accuracy.
  int finest_zoom = -1;
  double finest_error = 2.0;
  bool normals = true;  // extension octvertexnormals
  // Extension watermask: 256 x 256 bytes of a longitude/latitude box (west,
  // south, east, north), rows north to south, 255 water; none if empty.
  std::function<std::vector<uint8_t>(double, double, double, double)> water_mask;
  double threshold(int z, int roots_x) const;
};

// Ground metres of one sample step of zoom z at the equator (the widest).
double mesh_sample_metres(const tileformat::Tiling& tiling, int z, int steps);

// The tile's quantized-mesh bytes (not gzipped), from its grid and its
// errors after joining the neighbours' edges.
std::vector<uint8_t> encode_mesh_tile(const tileformat::Tiling& tiling, tileformat::TileId id,
                                      const TileGrid& grid, const MeshErrors& errors,
                                      const MeshTileOptions& options);

// The tiles a quantized-mesh export of the package holds, per zoom 0..max:
// the package's own; below its coarsest zoom the parents of those; and at
// zoom 0 every root (Cesium always loads both geodetic roots), 0 m where the
// package has no data.
std::vector<std::vector<tileformat::TileId>> mesh_tile_plan(TerrainPackage& package);

// layer.json (Cesium's CesiumTerrainProvider reads it): tiles template with
// {version}, TMS rows, projection, extensions, availability of `plan`.
std::string layer_json(const TerrainPackage& package,
                       const std::vector<std::vector<tileformat::TileId>>& plan,
                       const std::string& name, const std::string& description, bool normals,
                       bool water_mask = false);

}  // namespace globe::web
