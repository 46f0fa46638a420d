// Sky-view factor (see sky_view.hpp).
#include "analysis/sky_view.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace globe {
namespace {

// Steps 1..kFineSteps are one sample apart; further out each is kGrowth
// times the distance of the last (a horizon far away changes slowly with
// distance, so this keeps a ray at ~60 steps for 10 km over 30 m samples).
constexpr int kFineSteps = 12;
constexpr double kGrowth = 1.07;

}  // namespace

int sky_view_halo(const SkyViewSettings& s, double min_spacing_m, int steps) {
  const double h = std::ceil(s.radius_m / min_spacing_m) + 1;
  return static_cast<int>(std::min<double>(h, 2.0 * steps));
}

SkyViewScan::SkyViewScan(const SkyViewSettings& s, GroundSpacing sp) {
  for (int k = 0; k < s.directions; ++k) {
    const double az = 2 * std::numbers::pi * k / s.directions;           // clockwise from north
    const double ex = std::sin(az) / sp.dx, ey = -std::cos(az) / sp.dy;  // samples per metre
    // One sample along the ray's major axis; never past the radius, so that
    // a zoom coarser than the radius still sees the slope of its own cells.
    const double unit = std::min(1 / std::max(std::abs(ex), std::abs(ey)), s.radius_m);
    std::vector<Step> ray;
    double dist = 0;
    for (int j = 1;; ++j) {
      dist = j <= kFineSteps ? unit * j : dist * kGrowth;
      if (dist > s.radius_m * (1 + 1e-9)) break;
      ray.push_back({ex * dist, ey * dist, 1 / dist});
    }
    rays_.push_back(std::move(ray));
  }
}

double SkyViewScan::factor(const HeightWindow& w, int x, int y) const {
  const double h0 = w.height(x, y);
  double sum = 0;
  for (const auto& ray : rays_) {
    double best = 0;  // tangent of the horizon's elevation, >= 0
    for (const Step& s : ray) {
      const double fx = x + s.dx, fy = y + s.dy;
      const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
      if (!w.inside(x0, y0) || !w.inside(x0 + 1, y0 + 1)) break;
      if (!w.valid(x0, y0) || !w.valid(x0 + 1, y0) || !w.valid(x0, y0 + 1) ||
          !w.valid(x0 + 1, y0 + 1))
        break;
      const double tx = fx - x0, ty = fy - y0;
      const double top = w.height(x0, y0) + tx * (w.height(x0 + 1, y0) - w.height(x0, y0));
      const double bottom =
          w.height(x0, y0 + 1) + tx * (w.height(x0 + 1, y0 + 1) - w.height(x0, y0 + 1));
      const double h = top + ty * (bottom - top);
      best = std::max(best, (h - h0) * s.inv_distance);
    }
    sum += best / std::sqrt(1 + best * best);  // sin(atan(best))
  }
  return 1 - sum / static_cast<double>(rays_.size());
}

}  // namespace globe
