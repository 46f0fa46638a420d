// The significance filter (see significance.hpp).
#include "bundle/significance.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace globe {
namespace {

constexpr int kWindowX = 2, kWindowY = 1;  // tiles on each side: a 5 x 3 tile view

uint64_t tile_key(int64_t x, int64_t y) {
  return uint64_t(x) << 32 | uint64_t(y);
}

// The tiles of zoom z a flow's parts pass through (sorted, unique): each
// segment sampled at a quarter of the tile size, columns wrapped on
// wrapping tilings, rows clamped.
class TileWalk {
 public:
  TileWalk(const tileformat::Tiling& t, int z)
      : t_(t),
        size_(t.tile_size(z)),
        nx_(int64_t(t.tiles_x(z))),
        ny_(int64_t(t.tiles_y(z))),
        wraps_(t.wraps_x()) {}

  const std::vector<uint64_t>& tiles(const WeightedFlow& f) {
    out_.clear();
    for (const auto& part : f.parts)
      for (size_t i = 0; i < part.size(); ++i) {
        if (i == 0) {
          add(part[0]);
          continue;
        }
        const XY a = part[i - 1], b = part[i];
        const double len = std::hypot(b.x - a.x, b.y - a.y);
        const int steps = static_cast<int>(std::ceil(len / (size_ / 4)));
        for (int k = 1; k <= steps; ++k) {
          const double s = double(k) / steps;
          add({a.x + s * (b.x - a.x), a.y + s * (b.y - a.y)});
        }
        if (steps == 0) add(b);
      }
    std::sort(out_.begin(), out_.end());
    out_.erase(std::unique(out_.begin(), out_.end()), out_.end());
    return out_;
  }

  int64_t wrap_x(int64_t x) const { return wraps_ ? ((x % nx_) + nx_) % nx_ : x; }
  int64_t tiles_y() const { return ny_; }
  int64_t tiles_x() const { return nx_; }

 private:
  void add(XY p) {
    const int64_t x = wrap_x(static_cast<int64_t>(std::floor((p.x - t_.origin_x) / size_)));
    const int64_t y = std::clamp<int64_t>(
        static_cast<int64_t>(std::floor((t_.origin_y - p.y) / size_)), 0, ny_ - 1);
    out_.push_back(tile_key(x, y));
  }

  const tileformat::Tiling& t_;
  double size_;
  int64_t nx_, ny_;
  bool wraps_;
  std::vector<uint64_t> out_;
};

}  // namespace

std::vector<uint32_t> significant_zooms(std::span<const WeightedFlow> flows,
                                        const tileformat::Tiling& tiling, int min_zoom,
                                        int max_zoom, const SignificanceOptions& options) {
  const uint32_t all = (max_zoom >= 31 ? ~0u : (2u << max_zoom) - 1) & ~((1u << min_zoom) - 1);
  std::vector<uint32_t> zooms(flows.size(), 0);
  std::vector<size_t> pending;  // flows heavy enough to show, not yet significant
  for (size_t i = 0; i < flows.size(); ++i)
    if (flows[i].weight >= options.min_weight) {
      if (options.share > 0)
        pending.push_back(i);
      else
        zooms[i] = all;
    }
  for (int z = min_zoom; z <= max_zoom && !pending.empty(); ++z) {
    TileWalk walk(tiling, z);
    // The heaviest flow through each tile.
    std::unordered_map<uint64_t, double> heaviest;
    for (const WeightedFlow& f : flows)
      for (uint64_t t : walk.tiles(f)) {
        double& h = heaviest[t];
        h = std::max(h, f.weight);
      }
    auto window = [&](uint64_t key) {
      const int64_t x = int64_t(key >> 32), y = int64_t(key & 0xffffffffu);
      double h = 0;
      for (int64_t dy = -kWindowY; dy <= kWindowY; ++dy) {
        if (y + dy < 0 || y + dy >= walk.tiles_y()) continue;
        for (int64_t dx = -kWindowX; dx <= kWindowX; ++dx) {
          const int64_t wx = walk.wrap_x(x + dx);
          if (wx < 0 || wx >= walk.tiles_x()) continue;
          if (auto it = heaviest.find(tile_key(wx, y + dy)); it != heaviest.end())
            h = std::max(h, it->second);
        }
      }
      return h;
    };
    const uint32_t from_here = all & ~((1u << z) - 1);
    std::erase_if(pending, [&](size_t i) {
      double lightest_view = 1e300;
      for (uint64_t t : walk.tiles(flows[i]))
        lightest_view = std::min(lightest_view, window(t));
      if (flows[i].weight < options.share * lightest_view) return false;
      zooms[i] = from_here;
      return true;
    });
  }
  for (size_t i : pending)  // zoomed in all the way, every flow shows
    zooms[i] = 1u << max_zoom;
  return zooms;
}

}  // namespace globe
