// Raster-DEM tiles as terrain blocks (see raster_dem_reader.hpp). Reads
// through the RasterTileFetcher only; decodes with lib/runtime's PNG and
// WebP decoders; writes nothing but its caches.
//
// Height step, measured on Terrarium tiles that `globe-tiler export --format
// terrarium` made from samples/data (all blocks of each, as tile() makes
// them: zstd level 1, byte planes; time per block from a cold reader, PNG
// decoding and the neighbourhood's node errors included):
//   step      etopo20 z0-3 (85 blocks)   jacksboro z0-11 (35 blocks)
//   1/256 m   8.65 MB, 9.7 ms            561 kB, 5.4 ms
//   1/64 m    7.45 MB, 8.7 ms            519 kB, 4.8 ms
//   0.05 m    6.33 MB, 8.4 ms            512 kB, 5.2 ms
//   0.1 m     5.64 MB, 8.8 ms            447 kB, 5.1 ms
// 1/256 m gives the most bytes and, past |q| = 1.4 million (5,500 m), the
// error tree's 64-bit arithmetic; 1/64 m is the finest binary step without
// either, and its 8 mm rounding is below what any source holds. The blob is
// decoded at once, so its size only matters while it is passed on.
#include "data/raster_dem_reader.hpp"
#include "data/web_mercator.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "runtime/jpeg_webp_decoders.hpp"
#include "runtime/png_codec.hpp"
#include "tileformat/error.hpp"

namespace globe::viewer {
namespace {

using tileformat::TileId;

constexpr float kNoData = std::numeric_limits<float>::quiet_NaN();

bool is_png(std::span<const uint8_t> b) {
  static const uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  return b.size() >= 8 && std::memcmp(b.data(), kSignature, 8) == 0;
}

bool is_webp(std::span<const uint8_t> b) {
  return b.size() >= 12 && std::memcmp(b.data(), "RIFF", 4) == 0 &&
         std::memcmp(b.data() + 8, "WEBP", 4) == 0;
}

const char* encoding_name(DemEncoding e) {
  return e == DemEncoding::kTerrarium ? "Terrarium" : "Terrain-RGB";
}

}  // namespace

double dem_pixel_height(DemEncoding encoding, uint8_t r, uint8_t g, uint8_t b, uint8_t a) {
  if (a == 0) return std::numeric_limits<double>::quiet_NaN();
  if (encoding == DemEncoding::kTerrarium) return r * 256.0 + g + b / 256.0 - 32768.0;
  return -10000.0 + (r * 65536.0 + g * 256.0 + b) * 0.1;
}

double dem_height_step(DemEncoding encoding) {
  return encoding == DemEncoding::kTerrarium ? 1.0 / 64 : 0.1;
}

RasterDemReader::RasterDemReader(RasterTileFetcher& fetcher, DemEncoding encoding)
    : fetcher_(fetcher),
      encoding_(encoding),
      tiling_(tileformat::Tiling::webmercator()),
      min_zoom_(std::clamp(fetcher.min_zoom(), 0, tileformat::kMaxZoom)),
      max_zoom_(std::clamp(fetcher.max_zoom(), 0, tileformat::kMaxZoom)),
      blocks_(
          kBlockSize, kLattice, dem_height_step(encoding),
          [this](TileId id) { return samples(id); }, kCachedBlocks, tiling_) {
  const std::array<double, 4> b = fetcher.bounds();
  mercator_bounds_ = {mercator_x(std::clamp(b[0], -180.0, 180.0)), mercator_y(b[1]),
                      mercator_x(std::clamp(b[2], -180.0, 180.0)), mercator_y(b[3])};
  SynthesizedTerrain t;
  t.name = fetcher.name();
  t.description = std::string(encoding_name(encoding)) + " elevation tiles from " + fetcher.name() +
                  ", made into terrain blocks by globe-view";
  t.block_size = kBlockSize;
  t.lattice = kLattice;
  t.height_step = dem_height_step(encoding);
  t.min_zoom = min_zoom_;
  t.max_zoom = max_zoom_;
  t.lonlat = {b[0], b[1], b[2], b[3]};
  metadata_ = terrain_metadata_for(t);
  // Coarser zooms leave out what finer ones show: CesiumJS's estimate for
  // heightmaps of 256 samples a tile (block_synthesizer.hpp).
  blocks_.set_level_error(
      [max = max_zoom_](int z) { return z >= max ? 0.0 : cesium_level_error_m(z, 256, 1); });
}

RasterDemReader::RasterDemReader(std::unique_ptr<RasterTileFetcher> fetcher, DemEncoding encoding)
    : RasterDemReader(
          fetcher ? *fetcher : throw std::invalid_argument("raster-DEM reader: no fetcher"),
          encoding) {
  owned_ = std::move(fetcher);
}

bool RasterDemReader::in_bounds(TileId id) const {
  if (id.z < min_zoom_ || id.z > max_zoom_ || !tiling_.contains(id)) return false;
  const tileformat::TileRange r = tiling_.tiles_covering(mercator_bounds_, id.z);
  return !r.empty() && id.x >= r.min_x && id.x <= r.max_x && id.y >= r.min_y && id.y <= r.max_y;
}

std::optional<TileId> RasterDemReader::neighbour(TileId id, int dx, int dy) const {
  const int64_t n = static_cast<int64_t>(tiling_.tiles_x(id.z));
  const int64_t y = int64_t{id.y} + dy;
  if (y < 0 || y >= n) return std::nullopt;              // beyond a pole
  const int64_t x = ((int64_t{id.x} + dx) % n + n) % n;  // across the antimeridian
  return TileId{id.z, static_cast<uint32_t>(x), static_cast<uint32_t>(y)};
}

std::shared_ptr<const RasterDemReader::Decoded> RasterDemReader::fetch_and_decode(TileId id) const {
  auto d = std::make_shared<Decoded>();
  if (!in_bounds(id)) return d;
  std::optional<std::vector<uint8_t>> bytes;
  try {
    bytes = fetcher_.fetch(id);
  } catch (const tileformat::PackageError&) {
    throw;
  } catch (const std::exception& e) {
    throw tileformat::PackageError(fetcher_.name() + " (tile " + id.str() + "): " + e.what());
  }
  if (!bytes) return d;
  const std::string where = fetcher_.name() + " (tile " + id.str() + ")";
  int w = 0, h = 0;
  std::vector<uint8_t> rgba;
  try {
    if (is_png(*bytes))
      rgba = decode_png_rgba(bytes->data(), bytes->size(), w, h);
    else if (is_webp(*bytes))
      rgba = decode_webp_rgba(bytes->data(), bytes->size(), w, h);
    else
      throw tileformat::PackageError(where + ": neither PNG nor WebP; " + encoding_name(encoding_) +
                                     " tiles must be one of them");
  } catch (const tileformat::PackageError&) {
    throw;
  } catch (const std::exception& e) {
    throw tileformat::PackageError(where + ": " + e.what());
  }
  if (w != kTilePx || h != kTilePx)
    throw tileformat::PackageError(where + ": a " + std::to_string(w) + " x " + std::to_string(h) +
                                   " tile; raster-DEM tiles must be 256 x 256");
  d->present = true;
  d->h.resize(static_cast<size_t>(kTilePx) * kTilePx);
  for (size_t i = 0; i < d->h.size(); ++i) {
    const uint8_t* p = &rgba[4 * i];
    d->h[i] = static_cast<float>(dem_pixel_height(encoding_, p[0], p[1], p[2], p[3]));
  }
  return d;
}

std::shared_ptr<const RasterDemReader::Decoded> RasterDemReader::source(TileId id) {
  return tiles_.get(id, [&] { return fetch_and_decode(id); });
}

std::optional<std::vector<float>> RasterDemReader::samples(TileId id) {
  if (!in_bounds(id)) return std::nullopt;
  request(std::span(&id, 1), 1);  // the whole neighbourhood at once, then wait for each
  const std::shared_ptr<const Decoded> own = source(id);
  if (!own->present) return std::nullopt;
  std::shared_ptr<const Decoded> around[3][3];
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      if (auto t = neighbour(id, dx, dy)) {
        auto d = (dx == 0 && dy == 0) ? own : source(*t);
        if (d->present) around[dy + 1][dx + 1] = std::move(d);
      }
  // Pixel (c, r) of the 3 x 3 tiles, c and r in -kTilePx .. 2 * kTilePx - 1
  // relative to the own tile; NaN where there is none.
  auto pixel = [&](int c, int r) -> float {
    const int tx = c < 0 ? 0 : c < kTilePx ? 1 : 2, ty = r < 0 ? 0 : r < kTilePx ? 1 : 2;
    const Decoded* t = around[ty][tx].get();
    if (!t) return kNoData;
    const int lc = c - (tx - 1) * kTilePx, lr = r - (ty - 1) * kTilePx;
    return t->h[static_cast<size_t>(lr) * kTilePx + lc];
  };
  std::vector<float> out(static_cast<size_t>(kBlockSize) * kBlockSize);
  for (int j = 0; j < kBlockSize; ++j)
    for (int i = 0; i < kBlockSize; ++i) {
      // The four pixel centres around corner (i, j), in one order for every
      // block, so both blocks of an edge add the same numbers alike.
      double sum = 0;
      int count = 0;
      for (int r = j - 1; r <= j; ++r)
        for (int c = i - 1; c <= i; ++c) {
          const float v = pixel(c, r);
          if (std::isnan(v)) continue;
          sum += v;
          ++count;
        }
      out[static_cast<size_t>(j) * kBlockSize + i] =
          count ? static_cast<float>(sum / count) : kNoData;
    }
  return out;
}

std::optional<std::vector<uint8_t>> RasterDemReader::tile(TileId id) {
  {
    std::lock_guard lock(mutex_);
    if (absent_.count(id)) return std::nullopt;
  }
  // The block's error tree reads its neighbours' node errors, which need
  // their own neighbours' pixels: 5 x 5 source tiles, asked for at once.
  if (in_bounds(id)) request(std::span(&id, 1), 2);
  std::optional<std::vector<uint8_t>> blob = blocks_.blob(id);
  if (!blob) {
    std::lock_guard lock(mutex_);
    absent_.insert(id);
  }
  return blob;
}

bool RasterDemReader::has_tile(TileId id) {
  if (!in_bounds(id)) return false;
  std::lock_guard lock(mutex_);
  return !absent_.count(id);
}

std::vector<TileId> RasterDemReader::tile_ids(int zoom) {
  std::vector<TileId> out;
  if (zoom < min_zoom_ || zoom > max_zoom_) return out;
  const tileformat::TileRange r = tiling_.tiles_covering(mercator_bounds_, zoom);
  if (r.empty()) return out;
  const uint64_t w = uint64_t{r.max_x} - r.min_x + 1, h = uint64_t{r.max_y} - r.min_y + 1;
  const uint64_t stride = std::max<uint64_t>(1, (w * h + 65535) / 65536);
  for (uint64_t i = 0; i < w * h; i += stride)
    out.push_back(
        {zoom, static_cast<uint32_t>(r.min_x + i % w), static_cast<uint32_t>(r.min_y + i / w)});
  return out;  // row-major over (y, x): already in (y, x) order
}

void RasterDemReader::prefetch(std::span<const TileId> ids) {
  request(ids, 1);
}

void RasterDemReader::request(std::span<const TileId> ids, int reach) {
  std::vector<TileId> out;
  std::set<TileId> seen;
  auto add = [&](TileId t) {
    if (in_bounds(t) && seen.insert(t).second) out.push_back(t);
  };
  for (const TileId& id : ids)
    add(id);
  for (const TileId& id : ids)
    for (int dy = -reach; dy <= reach; ++dy)
      for (int dx = -reach; dx <= reach; ++dx)
        if (auto t = neighbour(id, dx, dy)) add(*t);
  // What is decoded (or being fetched) needs no request.
  std::erase_if(out, [&](const TileId& t) { return tiles_.contains(t); });
  if (!out.empty()) fetcher_.prefetch(out);
}

}  // namespace globe::viewer
