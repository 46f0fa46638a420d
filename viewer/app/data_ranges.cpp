// The analysis modes' ramps on this data (see data_ranges.hpp).
#include "app/data_ranges.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "runtime/analysis_package.hpp"
#include "runtime/terrain_package.hpp"
#include "tileformat/analysis_block.hpp"
#include "tileformat/mblock.hpp"

namespace globe::viewer {

namespace {

using tileformat::TileId;

constexpr size_t kBlocks = 16;

// Up to kBlocks of the ids, evenly spread.
std::vector<TileId> spread(const std::vector<TileId>& ids) {
  std::vector<TileId> out;
  for (size_t k = 0; k < std::min(kBlocks, ids.size()); ++k)
    out.push_back(ids[k * ids.size() / std::min(kBlocks, ids.size())]);
  return out;
}

double percentile(std::vector<double>& v, double p) {
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(double(v.size()) * p));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

}  // namespace

DataRanges measure_data_ranges(
    const std::string& terrain_path, const std::optional<std::string>& analysis_path,
    const std::function<std::pair<double, double>(tileformat::TileId)>& spacing_m) {
  DataRanges r;
  const TerrainPackage terrain = open_terrain_package(terrain_path);
  const std::vector<TileId> ids = spread(terrain.reader->tile_ids(terrain.max_zoom));
  std::vector<double> slopes;
  for (const TileId& id : ids) {
    const auto blob = terrain.reader->tile(id);
    if (!blob) continue;
    tileformat::MBlock b;
    try {
      b = tileformat::decode_mblock(*blob);
    } catch (const std::exception&) {
      continue;  // a broken block: the cache reports it when drawn
    }
    const auto [sx, sy] = spacing_m(id);
    if (sx <= 0 || sy <= 0) continue;
    for (int y = 1; y + 1 < b.size; ++y)
      for (int x = 1; x + 1 < b.size; ++x) {
        if (!b.is_valid(x - 1, y) || !b.is_valid(x + 1, y) || !b.is_valid(x, y - 1) ||
            !b.is_valid(x, y + 1))
          continue;
        const double gx = (b.height(x + 1, y) - b.height(x - 1, y)) / (2 * sx);
        const double gy = (b.height(x, y + 1) - b.height(x, y - 1)) / (2 * sy);
        slopes.push_back(std::atan(std::hypot(gx, gy)) * 180 / std::numbers::pi);
      }
  }
  if (!slopes.empty()) {
    r.slope_p95_deg = percentile(slopes, 0.95);
    r.slope_top_deg = std::clamp(2 * r.slope_p95_deg, 2.0, DataRanges::kSlopeTopDeg);
  }
  if (!analysis_path) return r;
  const AnalysisPackage analysis = open_analysis_package(*analysis_path);
  const auto& info = tileformat::analysis_layer_info(tileformat::AnalysisLayer::kSkyview);
  std::vector<double> sky;
  for (const TileId& id : spread(analysis.reader->tile_ids(analysis.max_zoom))) {
    const auto blob = analysis.reader->tile(id);
    if (!blob) continue;
    tileformat::AnalysisBlock b;
    try {
      b = tileformat::decode_analysis_block(*blob);
    } catch (const std::exception&) {
      continue;
    }
    for (size_t l = 0; l < b.layers.size(); ++l) {
      if (b.layers[l] != tileformat::AnalysisLayer::kSkyview) continue;
      for (uint16_t q : b.values[l])
        if (q != tileformat::kNoValue) sky.push_back(tileformat::dequantize(info, q));
    }
  }
  if (!sky.empty()) {
    r.sky_p5 = percentile(sky, 0.05);
    r.sky_low = std::clamp(2 * r.sky_p5 - 1, DataRanges::kSkyLow, 0.99);
  }
  return r;
}

}  // namespace globe::viewer
