// Heights of a terrain package anywhere (see terrain_sampler.hpp).
#include "terrain_sampler.hpp"

#include <algorithm>
#include <cmath>

#include "errors.hpp"
#include "tileformat/error.hpp"

namespace globe::web {

namespace {

uint64_t key(tileformat::TileId id) {
  return uint64_t(id.z) << 58 | uint64_t(id.x) << 29 | id.y;
}

}  // namespace

TerrainSampler::TerrainSampler(TerrainPackage& package, std::mutex& read_mutex, size_t max_blocks)
    : package_(package), read_mutex_(read_mutex), max_blocks_(std::max<size_t>(max_blocks, 4)) {}

const tileformat::MBlock* TerrainSampler::block(tileformat::TileId id) {
  const uint64_t k = key(id);
  if (auto it = cache_.find(k); it != cache_.end()) {
    ages_.splice(ages_.begin(), ages_, it->second.age);
    return it->second.block.get();
  }
  std::unique_ptr<tileformat::MBlock> b;
  std::optional<std::vector<uint8_t>> blob;
  {
    std::lock_guard lock(read_mutex_);
    blob = package_.reader->tile(id);
  }
  if (blob) {
    try {
      b = std::make_unique<tileformat::MBlock>(tileformat::decode_mblock(*blob));
    } catch (const tileformat::FormatError& e) {
      throw InputError(package_.reader->path() + ": tile " + id.str() + ": " + e.what() +
                       "; rebuild the package, or check it with globe-tiler validate");
    }
  }
  if (cache_.size() >= max_blocks_) {
    cache_.erase(ages_.back());
    ages_.pop_back();
  }
  ages_.push_front(k);
  const tileformat::MBlock* raw = b.get();
  cache_[k] = {std::move(b), ages_.begin()};
  return raw;
}

std::optional<double> TerrainSampler::height(double crs_x, double crs_y, int zoom) {
  const tileformat::Tiling& t = package_.tiling;
  for (int z = std::clamp(zoom, package_.min_zoom, package_.max_zoom); z >= package_.min_zoom;
       --z) {
    const double size = t.tile_size(z);
    double fx = (crs_x - t.origin_x) / size, fy = (t.origin_y - crs_y) / size;
    const double tiles_x = double(t.tiles_x(z)), tiles_y = double(t.tiles_y(z));
    if (t.wraps_x()) fx -= std::floor(fx / tiles_x) * tiles_x;
    // A point on the last edge belongs to the last tile.
    if (fx < 0 || fy < 0 || fx > tiles_x || fy > tiles_y) return std::nullopt;
    const uint32_t tx = static_cast<uint32_t>(std::min(std::floor(fx), tiles_x - 1));
    const uint32_t ty = static_cast<uint32_t>(std::min(std::floor(fy), tiles_y - 1));
    const tileformat::MBlock* b = block({z, tx, ty});
    if (!b) continue;
    const int steps = b->steps();
    const double u = (fx - tx) * steps, v = (fy - ty) * steps;
    const int i = std::clamp(static_cast<int>(std::floor(u)), 0, steps - 1);
    const int j = std::clamp(static_cast<int>(std::floor(v)), 0, steps - 1);
    const double a = u - i, c = v - j;
    return (1 - c) * ((1 - a) * b->height(i, j) + a * b->height(i + 1, j)) +
           c * ((1 - a) * b->height(i, j + 1) + a * b->height(i + 1, j + 1));
  }
  return std::nullopt;
}

}  // namespace globe::web
