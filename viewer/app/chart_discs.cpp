// The charts on screen (see chart_discs.hpp).
#include "app/chart_discs.hpp"

#include <algorithm>
#include <cmath>

namespace globe::viewer {

namespace {
constexpr float kCell = 64;
}

int64_t ChartDiscs::cell(float x, float y) {
  return (int64_t(std::floor(y / kCell)) << 32) ^ int64_t(uint32_t(int32_t(std::floor(x / kCell))));
}

void ChartDiscs::add(float x, float y, float r) {
  const auto index = static_cast<uint32_t>(discs_.size());
  discs_.push_back({x, y, r});
  for (float cy = std::floor((y - r) / kCell); cy <= std::floor((y + r) / kCell); ++cy)
    for (float cx = std::floor((x - r) / kCell); cx <= std::floor((x + r) / kCell); ++cx)
      cells_[cell(cx * kCell, cy * kCell)].push_back(index);
}

float ChartDiscs::radius_at(float x, float y) const {
  float r = 0;
  const auto it = cells_.find(cell(x, y));
  if (it == cells_.end()) return r;
  for (uint32_t c : it->second) {
    const Disc& d = discs_[c];
    if (std::hypot(x - d.x, y - d.y) <= d.r + 1) r = std::max(r, d.r);
  }
  return r;
}

std::vector<ScreenBox> ChartDiscs::obstacles() const {
  std::vector<ScreenBox> out;
  for (const Disc& d : discs_)
    out.push_back({d.x - 0.8f * d.r, d.y - 0.8f * d.r, d.x + 0.8f * d.r, d.y + 0.8f * d.r});
  return out;
}

}  // namespace globe::viewer
