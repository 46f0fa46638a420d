// Terrain blocks made from height grids (see block_synthesizer.hpp). Reads
// only through the GridFn it is given; writes nothing but its own cache.
#include "data/block_synthesizer.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "data/web_mercator.hpp"
#include "runtime/block_fill.hpp"
#include "runtime/error_tree.hpp"
#include "tileformat/mblock.hpp"
#include "tileformat/package_kinds.hpp"

namespace globe::viewer {
namespace {

using tileformat::TileId;

// The blob is decoded at once by the viewer's loader, never stored: the
// fastest coding (docs/tileformat.md §5.2 allows either).
constexpr int kZstdLevel = 1;

int checked_steps(int block_size, int lattice) {
  const int steps = block_size - 1;
  if (block_size < 3 || block_size > 4097 || lattice < 1 || lattice > 255)
    throw std::invalid_argument("block synthesizer: block size " + std::to_string(block_size) +
                                " / lattice " + std::to_string(lattice) +
                                " is not a valid block shape (tileformat §5.1)");
  tileformat::kpatch_depth(steps, lattice);  // throws for the rest
  return steps;
}

int32_t quantize(double h_m, double step) {
  const double q = std::round(h_m / step);
  const double lim = tileformat::kMaxQuantum;
  return static_cast<int32_t>(std::clamp(q, -lim, lim));
}

}  // namespace

BlockSynthesizer::BlockSynthesizer(int block_size, int lattice, double height_step, GridFn grid,
                                   size_t cached_blocks, tileformat::Tiling tiling,
                                   double fill_height_m)
    : size_(block_size),
      lattice_(lattice),
      step_(height_step),
      grid_(std::move(grid)),
      tiling_(std::move(tiling)),
      fill_q_(0),
      layouts_{tileformat::KPatchLayout(checked_steps(block_size, lattice), lattice, 0),
               tileformat::KPatchLayout(block_size - 1, lattice, 1)},
      blocks_(std::max<size_t>(cached_blocks, 1)) {
  if (!(height_step > 0) || !std::isfinite(height_step))
    throw std::invalid_argument("block synthesizer: the height step must be a positive number");
  if (!grid_) throw std::invalid_argument("block synthesizer: no grid function");
  fill_q_ = quantize(fill_height_m, step_);
}

std::optional<TileId> BlockSynthesizer::neighbour(TileId id, int dx, int dy) const {
  const int64_t nx = static_cast<int64_t>(tiling_.tiles_x(id.z)),
                ny = static_cast<int64_t>(tiling_.tiles_y(id.z));
  int64_t x = int64_t{id.x} + dx;
  const int64_t y = int64_t{id.y} + dy;
  if (y < 0 || y >= ny) return std::nullopt;  // beyond the poles (or a local tiling's edge)
  if (x < 0 || x >= nx) {
    if (!tiling_.wraps_x()) return std::nullopt;
    x = (x + nx) % nx;  // across the antimeridian
  }
  return TileId{id.z, static_cast<uint32_t>(x), static_cast<uint32_t>(y)};
}

void BlockSynthesizer::set_level_error(std::function<double(int z)> metres) {
  level_error_ = std::move(metres);
}

std::shared_ptr<const BlockSynthesizer::Block> BlockSynthesizer::make_block(TileId id) {
  auto b = std::make_shared<Block>();
  std::optional<std::vector<float>> heights = grid_(id);
  if (!heights) return b;
  const size_t n = static_cast<size_t>(size_) * size_;
  if (heights->size() != n)
    throw std::invalid_argument("block synthesizer: tile " + id.str() + " has " +
                                std::to_string(heights->size()) + " samples, not " +
                                std::to_string(n));
  b->present = true;
  b->q.resize(n);
  std::vector<uint8_t> valid(n, 1);
  bool holes = false;
  for (size_t i = 0; i < n; ++i) {
    const float h = (*heights)[i];
    if (std::isfinite(h)) {
      b->q[i] = quantize(h, step_);
    } else {
      valid[i] = 0;
      holes = true;
    }
  }
  if (holes) {
    fill_holes(b->q, valid, size_, fill_q_);
    b->valid = std::move(valid);
  }
  // Own samples only: the finest-zoom rule (see the header), under the
  // source's level error where one is known.
  b->node_errors = globe::node_errors(layouts_[id.diagonal()], b->q, b->valid,
                                      {nullptr, nullptr, nullptr, nullptr});
  if (level_error_) {
    const double m = level_error_(id.z);
    if (m > 0) {
      const auto floor_q = static_cast<uint32_t>(std::min(std::ceil(m / step_), 4.0e9));
      for (uint32_t& e : b->node_errors)
        e = std::max(e, floor_q);
    }
  }
  return b;
}

std::shared_ptr<const BlockSynthesizer::Block> BlockSynthesizer::block(TileId id) {
  return blocks_.get(id, [&] { return make_block(id); });
}

std::optional<std::vector<uint8_t>> BlockSynthesizer::blob(TileId id) {
  const std::shared_ptr<const Block> self = block(id);
  if (!self->present) return std::nullopt;
  std::shared_ptr<const Block> around[3][3];
  globe::Neighbourhood nb{};
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const std::optional<TileId> t = neighbour(id, dx, dy);
      if (!t) continue;
      auto& b = around[dy + 1][dx + 1];
      b = (dx == 0 && dy == 0) ? self : block(*t);
      if (b->present) nb[dy + 1][dx + 1] = &b->node_errors;
    }
  tileformat::MBlock m;
  m.size = size_;
  m.lattice = lattice_;
  m.step = step_;
  m.q = self->q;
  m.valid = self->valid;
  m.vertex_error = globe::vertex_errors(layouts_[id.diagonal()], nb);
  return tileformat::encode_mblock(m, kZstdLevel, tileformat::HeightCoding::kBytePlanes);
}

tileformat::MetadataMap terrain_metadata_for(const SynthesizedTerrain& t) {
  tileformat::TerrainMetadata m;
  tileformat::CommonMetadata& c = m.common;
  c.tiling = tileformat::Tiling::webmercator();
  c.name = t.name;
  c.format = tileformat::kMBlockFormat;
  c.type = "baselayer";
  c.description = t.description;
  const tileformat::Bounds lim = c.tiling.lonlat_limits();
  c.lonlat = {std::clamp(t.lonlat.min_x, lim.min_x, lim.max_x),
              std::clamp(t.lonlat.min_y, lim.min_y, lim.max_y),
              std::clamp(t.lonlat.max_x, lim.min_x, lim.max_x),
              std::clamp(t.lonlat.max_y, lim.min_y, lim.max_y)};
  c.min_zoom = t.min_zoom;
  c.max_zoom = t.max_zoom;
  const double deg = tileformat::kWebMercatorHalf / 180.0;  // metres per degree of longitude
  const tileformat::Bounds data{c.lonlat.min_x * deg, mercator_y(c.lonlat.min_y),
                                c.lonlat.max_x * deg, mercator_y(c.lonlat.max_y)};
  c.center_zoom = c.tiling.view_zoom(data, t.min_zoom, t.max_zoom);
  c.generator = "globe-view";
  c.command_line = "";
  c.inputs = {{t.name, 0}};
  m.resampling = "bilinear";  // samples on pixel corners, between four pixel centres
  m.block_size = t.block_size;
  m.lattice = t.lattice;
  m.height_step = t.height_step;
  m.fill_height = t.fill_height_m;
  tileformat::MetadataMap meta = tileformat::to_metadata(m);
  meta["globe:synthesized"] = "1";  // blocks not nested: the viewer hangs skirts
  return meta;
}

double cesium_level_error_m(int z, int samples_across, int roots_x) {
  constexpr double kEquatorialRadius = 6378137.0;
  return kEquatorialRadius * 2 * std::numbers::pi * 0.25 /
         (double(samples_across) * std::max(roots_x, 1)) / double(uint64_t{1} << z);
}

}  // namespace globe::viewer
