// RasterDemReader: a terrain source made of raster-DEM tiles on a foreign
// server — Terrarium or Mapbox Terrain-RGB, 256 x 256 PNG or WebP tiles in
// web mercator XYZ, pixel-is-area — read as if it were a terrain package: a
// TileReader whose tiles are MBlock blobs (block_synthesizer.hpp) and whose
// metadata is a terrain package's, so that such a source goes through the
// same KPatch LOD as a local package (no cracks, the same screen-space
// error). The bytes come from a RasterTileFetcher (XYZ template or PMTiles);
// this file decodes them (lib/runtime's PNG and WebP decoders) and touches
// nothing else.
//
// Samples. Block (z, x, y) has 257 x 257 samples, one step per source pixel:
// sample (i, j) lies on the CORNER between pixels (i-1, j-1) .. (i, j) of
// source tile (z, x, y), i.e. the bilinear interpolation at that corner —
// the mean of the four pixel centres around it, which can lie in up to four
// neighbouring source tiles (fetched; columns wrap at the antimeridian).
// Where some of the four are missing — beyond the poles, no neighbour tile,
// or a transparent (no data) pixel — the sample is the mean of those there,
// which at a straight edge is the clamp to the nearest pixel centre; with
// none there it is a hole. Every sample is a function of its global
// position alone, so neighbouring blocks share their edge samples exactly.
//
// Height step: Terrain-RGB 0.1 m, its own precision (q is the pixel code
// where the four pixels agree). Terrarium 1/64 m: Terrarium's precision is
// 1/256 m but a sample is the mean of four pixels (1/1024 m) and real
// sources carry nothing near that; 1/64 m keeps the rounding under 8 mm,
// is exact in binary, keeps |q| <= 704,000 for -11000..9000 m (far inside
// tileformat::kMaxQuantum, and small enough for the error tree's 32-bit
// arithmetic, docs/terrain.md "Error trees"), and gives smaller blocks than
// 1/256 m (raster_dem_reader.cpp has the measurement).
//
// Thread-safe: the viewer's loader threads call tile() at once.
#pragma once

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
#include <vector>

#include "data/block_synthesizer.hpp"
#include "data/fill_once_cache.hpp"
#include "data/raster_tile_fetcher.hpp"
#include "tileformat/tile_reader.hpp"
#include "tileformat/tiling.hpp"

namespace globe::viewer {

enum class DemEncoding {
  kTerrarium,   // h = R * 256 + G + B / 256 - 32768
  kTerrainRgb,  // h = -10000 + (R * 65536 + G * 256 + B) * 0.1
};

// The height in metres of one RGBA pixel; NaN where alpha is 0 (no data).
double dem_pixel_height(DemEncoding encoding, uint8_t r, uint8_t g, uint8_t b, uint8_t a);
// The height step of the blocks made from such tiles (see the top of this file).
double dem_height_step(DemEncoding encoding);

class RasterDemReader final : public tileformat::TileReader {
 public:
  static constexpr int kTilePx = 256;             // source tiles: 256 x 256 pixels
  static constexpr int kBlockSize = kTilePx + 1;  // one step per pixel
  static constexpr int kLattice = 16;             // as the tiler's default
  static constexpr size_t kCachedTiles = 96;      // decoded source tiles, 256 KiB each
  static constexpr size_t kCachedBlocks = 64;     // quantized grids + node errors

  // `fetcher` must outlive the reader. Zooms: the fetcher's min..max;
  // bounds: its bounds (clamped to web mercator's +-85.0511 degrees).
  RasterDemReader(RasterTileFetcher& fetcher, DemEncoding encoding);
  // The same, owning the fetcher (not null: std::invalid_argument).
  RasterDemReader(std::unique_ptr<RasterTileFetcher> fetcher, DemEncoding encoding);

  const std::map<std::string, std::string>& metadata() const override { return metadata_; }
  // The synthesized MBlock blob; nullopt where the source has no tile.
  // Reads the 5 x 5 source tiles around `id` (its neighbours' error trees
  // need their neighbours' pixels), asking for them all at once.
  // Throws tileformat::PackageError naming the URL for a tile that could not
  // be had or decoded (this block's or a neighbour's: its edges and errors
  // need them).
  std::optional<std::vector<uint8_t>> tile(tileformat::TileId id) override;
  // In the zoom range and bounds, and not answered absent.
  bool has_tile(tileformat::TileId id) override;
  // The tiles in bounds, in (y, x) order (at most 65,536: a spread beyond).
  std::vector<tileformat::TileId> tile_ids(int zoom) override;
  const std::string& path() const override { return fetcher_.name(); }
  // Asks the fetcher for the source tiles of these blocks and of their 3 x 3
  // neighbourhoods (the wanted ones first).
  void prefetch(std::span<const tileformat::TileId> ids) override;

  // The block's samples in metres (NaN: hole), kBlockSize^2, row-major from
  // the north row; nullopt where the source has no tile. What tile()
  // quantizes. Throws as tile().
  std::optional<std::vector<float>> samples(tileformat::TileId id);

 private:
  struct Decoded {
    bool present = false;
    std::vector<float> h;  // kTilePx^2 heights, NaN = no data
  };
  // The decoded source tile (decoded once; an LRU of kCachedTiles).
  std::shared_ptr<const Decoded> source(tileformat::TileId id);
  std::shared_ptr<const Decoded> fetch_and_decode(tileformat::TileId id) const;
  bool in_bounds(tileformat::TileId id) const;
  // Asks the fetcher for these source tiles and those within `reach` tiles
  // of them (the ids first), leaving out what is outside the bounds or
  // decoded already.
  void request(std::span<const tileformat::TileId> ids, int reach);
  std::optional<tileformat::TileId> neighbour(tileformat::TileId id, int dx, int dy) const;

  std::unique_ptr<RasterTileFetcher> owned_;  // null when the caller owns the fetcher
  RasterTileFetcher& fetcher_;
  DemEncoding encoding_;
  tileformat::Tiling tiling_;
  int min_zoom_, max_zoom_;
  tileformat::Bounds mercator_bounds_;  // the source's bounds in EPSG:3857 metres
  std::map<std::string, std::string> metadata_;

  FillOnceCache<tileformat::TileId, Decoded> tiles_{kCachedTiles};
  std::mutex mutex_;                     // guards absent_
  std::set<tileformat::TileId> absent_;  // blocks answered absent

  BlockSynthesizer blocks_;  // last: its GridFn calls samples()
};

}  // namespace globe::viewer
