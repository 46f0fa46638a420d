// Edge shading stretch (see edge_scale.hpp).
#include "app/edge_scale.hpp"

#include <algorithm>
#include <cmath>

#include "app/per_zoom.hpp"

namespace globe::viewer {

namespace {
constexpr size_t kEnough = 65536;
}

bool EdgeScale::add_samples(const LoadedBlock& b, double spacing_m) {
  if (b.analysis.empty() || b.id.z < 0 || b.id.z >= kZooms) return false;
  std::vector<float>& s = samples_[b.id.z];
  if (s.size() >= kEnough) return false;
  for (size_t i = 0; i < b.mask.size() && s.size() < kEnough; ++i) {
    const float plan = b.analysis[4 * i + 1];
    if (b.mask[i] && plan != 0) s.push_back(std::abs(plan) * static_cast<float>(spacing_m));
  }
  if (s.empty()) return false;
  std::vector<float> v = s;
  const size_t k = std::min(v.size() - 1, v.size() * 95 / 100);
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  scale_[b.id.z] = std::max(1e-6f, v[k]);
  return true;
}

std::array<float, EdgeScale::kZooms> EdgeScale::scales() const {
  return nearest_measured(scale_, 0.05f);
}

}  // namespace globe::viewer
