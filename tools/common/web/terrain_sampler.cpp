// Heights of a terrain package anywhere (see terrain_sampler.hpp).
#include "web/terrain_sampler.hpp"

#include <algorithm>
#include <cmath>

#include "runtime/errors.hpp"
#include "tileformat/error.hpp"

namespace globe::web {

uint64_t tile_key(tileformat::TileId id) {
  return uint64_t(id.z) << 58 | uint64_t(id.x) << 29 | id.y;
}

TerrainBlocks::TerrainBlocks(TerrainPackage& package, size_t max_bytes)
    : package_(package), cache_(max_bytes) {}

std::shared_ptr<const tileformat::MBlock> TerrainBlocks::block(tileformat::TileId id) {
  const uint64_t key = tile_key(id);
  std::shared_ptr<const tileformat::MBlock> b;
  if (cache_.get(key, b)) return b;
  std::optional<std::vector<uint8_t>> blob;
  {
    std::lock_guard lock(read_mutex_);
    blob = package_.reader->tile(id);
  }
  size_t bytes = 64;
  if (blob) {
    try {
      auto decoded = std::make_shared<tileformat::MBlock>(tileformat::decode_mblock(*blob));
      bytes += decoded->q.size() * sizeof(int32_t) + decoded->valid.size() +
               decoded->vertex_error.size() * sizeof(uint32_t);
      b = std::move(decoded);
    } catch (const tileformat::FormatError& e) {
      throw InputError(package_.reader->path() + ": tile " + id.str() + ": " + e.what() +
                       "; rebuild the package, or check it with globe-tiler validate");
    }
  }
  cache_.put(key, b, bytes);
  return b;
}

const tileformat::MBlock* TerrainSampler::block(tileformat::TileId id) {
  const uint64_t key = tile_key(id);
  int k = 0;
  while (k < kRecent - 1 && recent_[size_t(k)].key != key)
    ++k;
  Recent found = recent_[size_t(k)].key == key ? std::move(recent_[size_t(k)])
                                               : Recent{key, blocks_.block(id)};
  // Move the others down one, the found (or new) block first.
  for (; k > 0; --k)
    recent_[size_t(k)] = std::move(recent_[size_t(k) - 1]);
  recent_[0] = std::move(found);
  return recent_[0].block.get();
}

namespace {

// A coordinate's place along one axis of a zoom's tiles: tile, the sample
// cell in it and the fraction across that cell; tile < 0 outside.
struct AxisPlace {
  int64_t tile = -1;
  int cell = 0;
  double frac = 0;
};

AxisPlace place(double f, double tiles, bool wraps, int steps) {
  if (wraps) f -= std::floor(f / tiles) * tiles;
  // A point on the last edge belongs to the last tile.
  if (!(f >= 0 && f <= tiles)) return {};
  const double tile = std::min(std::floor(f), tiles - 1);
  const double u = (f - tile) * steps;
  const int cell = std::clamp(static_cast<int>(std::floor(u)), 0, steps - 1);
  return {int64_t(tile), cell, u - cell};
}

}  // namespace

void TerrainSampler::heights(const std::vector<double>& xs, const std::vector<double>& ys, int zoom,
                             std::vector<double>& out) {
  const TerrainPackage& package = blocks_.package();
  const tileformat::Tiling& t = package.tiling;
  const int steps = package.block_size - 1;
  out.assign(xs.size() * ys.size(), NAN);
  size_t missing = out.size();
  std::vector<AxisPlace> cols(xs.size()), rows(ys.size());
  for (int z = std::clamp(zoom, package.min_zoom, package.max_zoom);
       z >= package.min_zoom && missing > 0; --z) {
    const double size = t.tile_size(z);
    for (size_t k = 0; k < xs.size(); ++k)
      cols[k] = place((xs[k] - t.origin_x) / size, double(t.tiles_x(z)), t.wraps_x(), steps);
    for (size_t j = 0; j < ys.size(); ++j)
      rows[j] = place((t.origin_y - ys[j]) / size, double(t.tiles_y(z)), false, steps);
    for (size_t j = 0; j < ys.size(); ++j) {
      const AxisPlace r = rows[j];
      if (r.tile < 0) continue;
      double* line = &out[j * xs.size()];
      for (size_t k = 0; k < xs.size(); ++k) {
        const AxisPlace c = cols[k];
        if (c.tile < 0 || !std::isnan(line[k])) continue;
        const tileformat::MBlock* b = block({z, uint32_t(c.tile), uint32_t(r.tile)});
        if (!b) continue;
        const int i = c.cell, jj = r.cell;
        const double a = c.frac, v = r.frac;
        line[k] = (1 - v) * ((1 - a) * b->height(i, jj) + a * b->height(i + 1, jj)) +
                  v * ((1 - a) * b->height(i, jj + 1) + a * b->height(i + 1, jj + 1));
        --missing;
      }
    }
  }
}

}  // namespace globe::web
