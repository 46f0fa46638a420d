// Analysis blocks: per-sample terrain analytics of one terrain tile
// (docs/tileformat.md §9). Same tile id and sample grid as the terrain
// block; each layer's values quantized to u16 (value = offset + q * scale,
// kNoValue where the layer has none; the accumulation layer quantizes
// log2 of the value). encode/decode are exact inverses.
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace tileformat {

enum class AnalysisLayer : uint8_t {
  kSlope = 1,             // degrees from horizontal, 0..90
  kAspect = 2,            // degrees clockwise from north the slope faces, 0..360
  kProfileCurvature = 3,  // 1/m along the slope line: > 0 convex (crests), < 0 concave
  kPlanCurvature = 4,     // 1/m across the slope line: > 0 ridges (flow diverges), < 0 valleys
  kSkyview = 5,           // sky-view factor: share of the sky seen, 0..1 (1 = open plane)
  kFlowDirection = 6,     // D8 receiver: 0 none (drains off the data), 1..8 N, NE, E .. NW
  kFlowAccumulation = 7,  // upstream area in m^2, the sample's own cell included
};

struct AnalysisLayerInfo {
  AnalysisLayer layer;
  const char* name;  // as on the command line and in globe:layers
  const char* unit;
  double scale, offset;  // value = offset + q * scale
  bool log2 = false;     // then value = 2^(offset + q * scale)
};

inline constexpr uint16_t kNoValue = 65535;

// Every layer the format knows, in id order.
const std::vector<AnalysisLayerInfo>& analysis_layers();
const AnalysisLayerInfo& analysis_layer_info(AnalysisLayer layer);
std::optional<AnalysisLayer> analysis_layer_by_name(const std::string& name);

// q for a value: rounded to the nearest quantum, clamped to 0..kNoValue - 1.
uint16_t quantize(const AnalysisLayerInfo& info, double value);
inline double dequantize(const AnalysisLayerInfo& info, uint16_t q) {
  const double v = info.offset + q * info.scale;
  return info.log2 ? std::exp2(v) : v;
}

struct AnalysisBlock {
  int size = 0;                               // samples per side, as the terrain block
  std::vector<AnalysisLayer> layers;          // ascending ids, no repeats
  std::vector<std::vector<uint16_t>> values;  // per layer, size * size, row-major from north
};

// Preconditions checked (std::invalid_argument). `zstd_level`: of the layers
// stored as residuals; the flow layers' codings (packed directions, areas
// predicted along them) always go at level 1 (§9 says why).
std::vector<uint8_t> encode_analysis_block(const AnalysisBlock& block, int zstd_level = 9);
// Throws FormatError citing §4/§9 for anything malformed.
AnalysisBlock decode_analysis_block(std::span<const uint8_t> blob);

}  // namespace tileformat
