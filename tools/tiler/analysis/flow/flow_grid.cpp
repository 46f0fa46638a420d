// Flow grid geometry (see flow_grid.hpp).
#include "analysis/flow/flow_grid.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "analysis/terrain_derivatives.hpp"

namespace globe::flow {

int Chunk::perimeter_index(int x, int y) const {
  if (w == 1 || h == 1) return y * w + x;
  if (y == 0) return x;
  if (y == h - 1) return w + x;
  if (x == 0) return 2 * w + (y - 1);
  if (x == w - 1) return 2 * w + (h - 2) + (y - 1);
  return -1;
}

void Chunk::perimeter_cell(int i, int& x, int& y) const {
  if (w == 1 || h == 1) {
    x = i % w;
    y = i / w;
  } else if (i < w) {
    x = i, y = 0;
  } else if (i < 2 * w) {
    x = i - w, y = h - 1;
  } else if (i < 2 * w + h - 2) {
    x = 0, y = i - 2 * w + 1;
  } else {
    x = w - 1, y = i - 2 * w - (h - 2) + 1;
  }
}

namespace {

constexpr double kA = 6378137.0, kF = 1 / 298.257223563;
constexpr double kB = kA * (1 - kF), kE2 = kF * (2 - kF);
constexpr double kDeg = std::numbers::pi / 180;

// Area of the ellipsoid between the equator and latitude phi, per radian of
// longitude (the authalic zone formula).
double zone(double phi) {
  const double e = std::sqrt(kE2), s = std::sin(phi);
  return kB * kB / 2 * (s / (1 - kE2 * s * s) + std::log((1 + e * s) / (1 - e * s)) / (2 * e));
}

}  // namespace

std::vector<uint8_t> FlowGrid::present_chunks(const tileformat::Tiling& tiling, int zoom, int steps,
                                              const std::vector<tileformat::TileId>& finest,
                                              int64_t c, int64_t& chunks_x, int64_t& chunks_y) {
  const bool wrap = tiling.wrap_tiles() != 0;
  const int64_t cols = int64_t(tiling.tiles_x(zoom)) * steps;
  const int64_t rows = int64_t(tiling.tiles_y(zoom)) * steps;
  const int64_t width = wrap ? cols : cols + 1;
  chunks_x = std::max<int64_t>(1, cols / c);
  chunks_y = std::max<int64_t>(1, rows / c);
  if (wrap && cols % c != 0) chunks_x = 1;  // (C is at most one zoom-0 root wide)
  std::vector<uint8_t> present(size_t(chunks_x * chunks_y), 0);
  // Every chunk a tile's cells (edges included) fall in; steps and C are
  // powers of two, so the stride lands on the tile's end.
  const int64_t stride = std::min<int64_t>(c, steps);
  for (const tileformat::TileId& id : finest) {
    const int64_t x0 = int64_t(id.x) * steps, y0 = int64_t(id.y) * steps;
    for (int64_t y = y0; y <= y0 + steps; y += stride)
      for (int64_t x = x0; x <= x0 + steps; x += stride) {
        const int64_t xx = wrap ? x % width : x;
        present[size_t(std::min(y / c, chunks_y - 1) * chunks_x + std::min(xx / c, chunks_x - 1))] =
            1;
      }
  }
  return present;
}

double cell_area_m2(const tileformat::Tiling& t, int zoom, int steps, int64_t y) {
  const double sp = t.sample_spacing(zoom, steps);
  if (t.scheme == tileformat::Scheme::kLocal) return sp * sp;
  const double cy = t.origin_y - double(y) * sp;  // CRS y of the cell's centre
  double north = cy + sp / 2, south = cy - sp / 2, dlon = 0;
  if (t.scheme == tileformat::Scheme::kGeodetic) {
    north = std::clamp(north, -90.0, 90.0) * kDeg;
    south = std::clamp(south, -90.0, 90.0) * kDeg;
    dlon = sp * kDeg;
  } else {  // web mercator: lat = 2 atan(exp(y / a)) - pi / 2
    north = 2 * std::atan(std::exp(north / kA)) - std::numbers::pi / 2;
    south = 2 * std::atan(std::exp(south / kA)) - std::numbers::pi / 2;
    dlon = sp / kA;
  }
  return dlon * std::abs(zone(north) - zone(south));
}

FlowGrid::FlowGrid(const tileformat::Tiling& tiling, int zoom, int block_size,
                   const std::vector<tileformat::TileId>& finest, int64_t chunk)
    : tiling_(tiling), zoom_(zoom), steps_(block_size - 1), c_(chunk) {
  wrap_ = tiling.wrap_tiles() != 0;
  const int64_t cols = int64_t(tiling.tiles_x(zoom)) * steps_;
  const int64_t rows = int64_t(tiling.tiles_y(zoom)) * steps_;
  width_ = wrap_ ? cols : cols + 1;
  height_ = rows + 1;
  const std::vector<uint8_t> present =
      present_chunks(tiling, zoom, steps_, finest, c_, chunks_x_, chunks_y_);
  slots_.assign(present.size(), -1);
  for (int64_t r = 0; r < chunks_y_; ++r)
    for (int64_t c = 0; c < chunks_x_; ++c) {
      if (!present[size_t(r * chunks_x_ + c)]) continue;
      Chunk k;
      k.col = c, k.row = r;
      k.x0 = c * c_, k.y0 = r * c_;
      k.w = int((c + 1 == chunks_x_ ? width_ : (c + 1) * c_) - k.x0);
      k.h = int((r + 1 == chunks_y_ ? height_ : (r + 1) * c_) - k.y0);
      slots_[size_t(r * chunks_x_ + c)] = int(chunks_.size());
      chunks_.push_back(k);
    }
  dx_.resize(size_t(height_));
  dy_.resize(size_t(height_));
  area_.resize(size_t(height_));
  const int64_t last_tile_row = rows / steps_ - 1;
  for (int64_t y = 0; y < height_; ++y) {
    const int64_t tile_row = std::min(y / steps_, last_tile_row);
    const GroundSpacing g =
        ground_spacing(tiling, zoom, steps_, uint32_t(tile_row), int(y - tile_row * steps_));
    dx_[size_t(y)] = g.dx;
    dy_[size_t(y)] = g.dy;
    area_[size_t(y)] = std::max<uint64_t>(
        1, uint64_t(std::llround(cell_area_m2(tiling, zoom, steps_, y) * kAreaUnitsPerM2)));
  }
}

}  // namespace globe::flow
