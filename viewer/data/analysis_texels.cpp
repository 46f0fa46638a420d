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
  const std::vector<double> area = values(b, AnalysisLayer::kFlowAccumulation, 0);
  std::vector<float> t(area.size());
  for (size_t i = 0; i < area.size(); ++i)
    t[i] = area[i] > 0 ? static_cast<float>(std::log2(area[i])) : kNoFlow;
  return t;
}

}  // namespace globe::viewer
