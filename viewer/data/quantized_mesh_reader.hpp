// QuantizedMeshReader: a CesiumJS terrain tileset — quantized-mesh-1.0 tiles
// described by a layer.json — read as if it were a terrain package: a
// TileReader whose tiles are MBlock blobs (block_synthesizer.hpp) and whose
// metadata is a terrain package's, so that it goes through the same KPatch
// LOD as a local package. Requests go through the process's HttpClient
// (lib/net); tiles are decoded by quantized_mesh_decode and sampled on the
// block grid by mesh_grid; this file touches nothing else.
//
// layer.json: `tiles` (URL templates with {z} {x} {y} {version}, relative to
// the layer.json; spread over by x + y + z as CesiumJS does), `scheme` "tms"
// (rows from the south), `projection` "EPSG:4326" (the geodetic tiling: two
// roots at zoom 0, as tileformat's) or "EPSG:3857" (web mercator),
// `minzoom`/`maxzoom`, `bounds`, and `available`: per zoom, rectangles of
// TMS tiles. A zoom that `available` lists has exactly those tiles and no
// other is ever asked for; a zoom beyond the list (CesiumJS's
// metadataAvailability: the deeper zooms are announced by the tiles' own
// metadata, which this reader does not follow) is taken as whole inside
// `bounds`, and a 404/204 there is remembered as absent.
//
// Samples. Block (z, x, y) has kBlockSize² samples on the tile's corners
// (row 0 at the north) where the tiling puts them (docs/tileformat.md §2:
// evenly spaced in longitude and in latitude or mercator y; a tile's v is
// linear in latitude in both projections, so web mercator rows are mapped),
// each the mesh's height interpolated in the triangle holding it
// (mesh_grid.hpp). A sample on an edge shared with a
// neighbour tile is taken from the tile that owns it (docs/tileformat.md
// §2.1: the east tile owns a vertical edge, the south tile a horizontal
// one; a corner belongs to the first present of the tiles south-east,
// north-east, south-west and north-west of it), so neighbouring blocks
// share their edge samples exactly even though each tile quantizes its
// heights between its own minimum and maximum (and even where a producer's
// neighbouring tiles do not cut the same edge vertices: CesiumJS hides that
// with skirts, which the viewer does not draw). Each block therefore reads
// the tiles east, south and south-east of it (north-east where there is no
// east one).
//
// The blobs are BlockSynthesizer's, made from samples(): its node errors
// are floored by CesiumJS's geometric error of the level (the error
// producers cut quantized-mesh TINs to; none at the finest zoom), and it
// nests each block's samples at its parent's positions in the parent's
// block (block_synthesizer.hpp) — so those carry the coarser level's TIN,
// which for quantized-mesh can be kilometres off (the level error is 77 km
// at zoom 0 of a geodetic tileset; tests/quantized_mesh_reader_test.cpp
// measures both).
//
// Block size 257: our own export and globe-serve cut tiles from 257² blocks
// and put vertices on any of those samples at the finest zoom, so 257
// samples keep every vertex of such a tile on the grid; tiles of
// ctb-like producers (65² height maps) are sampled 4 times over, which
// costs rasterizing time, not accuracy. Height step 1/32 m: exact in binary,
// rounding under 1.6 cm — below a tile's own height quantum once its relief
// exceeds 1,000 m ((max - min) / 32767) — and |q| <= 352,000 for
// -11,000..+11,000 m, far inside tileformat::kMaxQuantum.
//
// Thread-safe: the viewer's loader threads call tile() at once.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "data/block_synthesizer.hpp"
#include "data/fill_once_cache.hpp"
#include "data/quantized_mesh_decode.hpp"
#include "net/http_client.hpp"
#include "tileformat/tile_reader.hpp"
#include "tileformat/tiling.hpp"

namespace globe::viewer {

class QuantizedMeshReader final : public tileformat::TileReader {
 public:
  static constexpr int kBlockSize = 257;
  static constexpr int kLattice = 16;              // as the tiler's default
  static constexpr double kHeightStep = 1.0 / 32;  // metres per quantum
  static constexpr size_t kCachedTiles = 96;       // sampled tiles, 258 KiB each
  static constexpr size_t kCachedBlocks = 64;      // quantized grids + node errors

  // Reads the layer.json at `url` (waiting for it). Throws InputError naming
  // the URL: unreachable, not JSON, not quantized-mesh-1.x, a scheme other
  // than tms, a projection other than EPSG:4326 / EPSG:3857, no tiles.
  // `client` must outlive the reader.
  QuantizedMeshReader(const std::string& url, net::HttpClient& client);
  // Cancels what is still asked for.
  ~QuantizedMeshReader() override;

  const std::map<std::string, std::string>& metadata() const override { return metadata_; }
  // The synthesized MBlock blob; nullopt where the tileset has no tile.
  // Throws tileformat::PackageError naming the URL for a tile that could not
  // be had or decoded (this block's or a neighbour's: its edges and errors
  // need them).
  std::optional<std::vector<uint8_t>> tile(tileformat::TileId id) override;
  // Listed as available (see the top) and not answered absent.
  bool has_tile(tileformat::TileId id) override;
  // The available tiles of the zoom in (y, x) order (at most 65,536: a
  // spread beyond).
  std::vector<tileformat::TileId> tile_ids(int zoom) override;
  const std::string& path() const override { return url_; }
  // Asks for these tiles now, the first most urgent.
  void prefetch(std::span<const tileformat::TileId> ids) override;
  // Cancels what is not fetched yet of these.
  void forget(std::span<const tileformat::TileId> ids) override;

  // The URL of a tile (TMS row, the layer.json's query appended).
  std::string tile_url(tileformat::TileId id) const;
  const tileformat::Tiling& tiling() const { return tiling_; }
  // The block's samples in metres (NaN: a hole in the mesh), kBlockSize²,
  // north row first, shared edges from their owners; nullopt where there is
  // no tile. What tile() quantizes. Throws as tile().
  std::optional<std::vector<float>> samples(tileformat::TileId id);

 private:
  struct TmsRect {
    uint32_t x0 = 0, x1 = 0, y0 = 0, y1 = 0;  // inclusive, TMS rows
  };
  // One request and its answer; the validated body's decoded mesh.
  struct Pending {
    net::RequestId request = 0;
    bool done = false;
    net::Response response;
    std::shared_ptr<const QuantizedMesh> mesh;  // decoded while validating
  };
  // What the client's callbacks touch: outlives the reader if need be.
  struct Shared {
    std::mutex mutex;
    std::condition_variable answered;
  };
  struct Sampled {
    bool present = false;
    std::vector<float> h;  // the tile's own samples (mesh_grid), kBlockSize²
  };

  bool listed(tileformat::TileId id) const;
  std::optional<tileformat::TileId> neighbour(tileformat::TileId id, int dx, int dy) const;
  // Under shared_->mutex.
  std::shared_ptr<Pending> ask(tileformat::TileId id, double priority);
  // The tile's own samples: fetched, decoded, sampled once (an LRU of
  // kCachedTiles).
  std::shared_ptr<const Sampled> own(tileformat::TileId id);
  std::shared_ptr<const Sampled> fetch_and_sample(tileformat::TileId id);

  std::string url_, query_;
  std::vector<std::string> templates_;  // absolute, {version} filled in
  net::HttpClient& client_;
  tileformat::Tiling tiling_;
  int min_zoom_ = 0, max_zoom_ = 0;
  tileformat::Bounds crs_bounds_;                // `bounds` in the tiling's CRS
  std::vector<std::vector<TmsRect>> available_;  // by zoom
  std::map<std::string, std::string> metadata_;

  std::shared_ptr<Shared> shared_;  // its mutex guards the members below
  std::unordered_map<uint64_t, std::shared_ptr<Pending>> pending_;  // by key(id)
  std::set<tileformat::TileId> absent_;                             // answered 404/204
  double next_priority_ = 0;  // later batches go after earlier ones
  FillOnceCache<tileformat::TileId, Sampled> tiles_{kCachedTiles};

  // Last (destroyed first: its GridFn calls samples()); made once the
  // layer.json gave the tiling.
  std::unique_ptr<BlockSynthesizer> blocks_;
};

}  // namespace globe::viewer
