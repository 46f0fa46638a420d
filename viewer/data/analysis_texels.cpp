// Analysis block -> texels (see analysis_texels.hpp).
#include "data/analysis_texels.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace globe::viewer {

using tileformat::AnalysisLayer;

namespace {

// The layer's dequantized values with `missing` where it has none; all
// `missing` when the block lacks the layer.
std::vector<double> values(const tileformat::AnalysisBlock& b, AnalysisLayer layer,
                           double missing) {
  const size_t n = size_t(b.size) * b.size;
  std::vector<double> out(n, missing);
  const auto it = std::find(b.layers.begin(), b.layers.end(), layer);
  if (it == b.layers.end()) return out;
  const auto& info = tileformat::analysis_layer_info(layer);
  const std::vector<uint16_t>& q = b.values[size_t(it - b.layers.begin())];
  for (size_t i = 0; i < n; ++i)
    if (q[i] != tileformat::kNoValue) out[i] = tileformat::dequantize(info, q[i]);
  return out;
}

}  // namespace

std::vector<float> analysis_texels(const tileformat::AnalysisBlock& b) {
  constexpr double kDeg = std::numbers::pi / 180;
  const size_t n = size_t(b.size) * b.size;
  const std::vector<double> sky = values(b, AnalysisLayer::kSkyview, 1),
                            plan = values(b, AnalysisLayer::kPlanCurvature, 0),
                            slope = values(b, AnalysisLayer::kSlope, 0),
                            aspect = values(b, AnalysisLayer::kAspect, NAN);
  std::vector<float> t(4 * n);
  for (size_t i = 0; i < n; ++i) {
    const double g = std::isnan(aspect[i]) ? 0 : std::tan(std::min(slope[i], 89.9) * kDeg);
    const double a = std::isnan(aspect[i]) ? 0 : aspect[i] * kDeg;
    t[4 * i] = static_cast<float>(sky[i]);
    t[4 * i + 1] = static_cast<float>(plan[i]);
    t[4 * i + 2] = static_cast<float>(g * std::sin(a));
    t[4 * i + 3] = static_cast<float>(g * std::cos(a));
  }
  return t;
}

std::vector<float> flow_texels(const tileformat::AnalysisBlock& b) {
  // D8 codes (tileformat §9): 1..8 north, north-east, east .. north-west.
  static constexpr int kDx[9] = {0, 0, 1, 1, 1, 0, -1, -1, -1};
  static constexpr int kDy[9] = {0, -1, -1, 0, 1, 1, 1, 0, -1};
  const std::vector<double> area = values(b, AnalysisLayer::kFlowAccumulation, 0),
                            code = values(b, AnalysisLayer::kFlowDirection, 0);
  std::vector<float> t(area.size() * kFlowTexel);
  for (size_t i = 0; i < area.size(); ++i) {
    const int c = std::clamp(static_cast<int>(std::lround(code[i])), 0, 8);
    t[kFlowTexel * i] = area[i] > 0 ? static_cast<float>(std::log2(area[i])) : kNoFlow;
    t[kFlowTexel * i + 1] = static_cast<float>(kDx[c]);
    t[kFlowTexel * i + 2] = static_cast<float>(kDy[c]);
  }
  return t;
}

}  // namespace globe::viewer
