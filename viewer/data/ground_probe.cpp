// Ground height under a point (see ground_probe.hpp).
#include "data/ground_probe.hpp"

#include <algorithm>
#include <cmath>

#include "runtime/errors.hpp"
#include "tileformat/error.hpp"

namespace globe::viewer {

GroundProbe::GroundProbe(const std::string& path) : package_(open_terrain_package(path)) {}

GroundProbe::~GroundProbe() = default;

const tileformat::MBlock* GroundProbe::block(tileformat::TileId id) {
  for (size_t i = 0; i < recent_.size(); ++i)
    if (recent_[i].first == id) {
      std::rotate(recent_.begin(), recent_.begin() + i, recent_.begin() + i + 1);
      return recent_.front().second ? &*recent_.front().second : nullptr;
    }
  std::optional<tileformat::MBlock> b;
  if (const auto blob = package_.reader->tile(id)) {
    try {
      b = tileformat::decode_mblock(*blob);
    } catch (const tileformat::FormatError&) {
      // A broken block: the viewer warns about it; the probe looks coarser.
    }
  }
  if (recent_.size() == kRecent) recent_.pop_back();
  recent_.insert(recent_.begin(), {id, std::move(b)});
  return recent_.front().second ? &*recent_.front().second : nullptr;
}

std::optional<double> GroundProbe::height_at(double x, double y) {
  const tileformat::Tiling& t = package_.tiling;
  for (int z = package_.max_zoom; z >= package_.min_zoom; --z) {
    const double s = t.tile_size(z);
    const double col = std::floor((x - t.origin_x) / s), row = std::floor((t.origin_y - y) / s);
    if (col < 0 || row < 0 || col >= double(t.tiles_x(z)) || row >= double(t.tiles_y(z)))
      return std::nullopt;  // off the tiling
    const tileformat::MBlock* block = this->block({z, uint32_t(col), uint32_t(row)});
    if (!block) continue;
    const tileformat::MBlock& b = *block;
    const tileformat::Bounds tb = t.tile_bounds({z, uint32_t(col), uint32_t(row)});
    const int n = b.steps();
    const double fx = std::clamp((x - tb.min_x) / s * n, 0.0, double(n)),
                 fy = std::clamp((tb.max_y - y) / s * n, 0.0, double(n));
    const int x0 = std::min(int(fx), n - 1), y0 = std::min(int(fy), n - 1);
    const double ax = fx - x0, ay = fy - y0;
    double sum = 0, weight = 0;
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        const double w = (dx ? ax : 1 - ax) * (dy ? ay : 1 - ay);
        if (w <= 0 || !b.is_valid(x0 + dx, y0 + dy)) continue;
        sum += w * b.height(x0 + dx, y0 + dy);
        weight += w;
      }
    if (weight > 0) return sum / weight;
    // A hole in this block: a coarser one may hold data there.
  }
  return std::nullopt;
}

}  // namespace globe::viewer
