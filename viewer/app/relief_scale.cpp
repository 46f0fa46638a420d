// Relief stretch per zoom (see relief_scale.hpp).
#include "app/relief_scale.hpp"

#include <algorithm>
#include <cmath>

#include "app/per_zoom.hpp"

namespace globe::viewer {

namespace {
constexpr size_t kEnough = 65536;
}

bool ReliefScale::add_samples(const LoadedBlock& b, double spacing_x_m, double spacing_y_m) {
  if (b.id.z < 0 || b.id.z >= kZooms || spacing_x_m <= 0 || spacing_y_m <= 0) return false;
  std::vector<float>& s = slopes_[b.id.z];
  if (s.size() >= kEnough) return false;
  const int n = static_cast<int>(std::lround(std::sqrt(double(b.heights.size()))));
  auto at = [&](int x, int y) { return size_t(y) * n + x; };
  // Central differences at every other interior sample with data around it.
  for (int y = 1; y + 1 < n && s.size() < kEnough; y += 2)
    for (int x = 1; x + 1 < n && s.size() < kEnough; x += 2) {
      if (!b.mask[at(x - 1, y)] || !b.mask[at(x + 1, y)] || !b.mask[at(x, y - 1)] ||
          !b.mask[at(x, y + 1)])
        continue;
      const double gx = (b.heights[at(x + 1, y)] - b.heights[at(x - 1, y)]) / (2 * spacing_x_m);
      const double gy = (b.heights[at(x, y + 1)] - b.heights[at(x, y - 1)]) / (2 * spacing_y_m);
      s.push_back(static_cast<float>(std::hypot(gx, gy)));
    }
  if (s.empty()) return false;
  std::vector<float> v = s;
  const size_t k = std::min(v.size() - 1, v.size() * 90 / 100);
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  const float stretch = std::clamp(kTargetSlope / std::max(v[k], 1e-6f), 1.0f, kMaxStretch);
  if (stretch == stretch_[b.id.z]) return false;
  stretch_[b.id.z] = stretch;
  return true;
}

std::array<float, ReliefScale::kZooms> ReliefScale::stretches() const {
  return nearest_measured(stretch_, 1.0f);
}

}  // namespace globe::viewer
