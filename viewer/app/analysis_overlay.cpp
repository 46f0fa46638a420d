// Opening and checking the analysis overlay (see analysis_overlay.hpp).
#include "app/analysis_overlay.hpp"

#include <algorithm>

#include "app/package_set.hpp"
#include "runtime/analysis_package.hpp"
#include "runtime/errors.hpp"

namespace globe::viewer {

using tileformat::AnalysisLayer;

AnalysisOverlay open_analysis_overlay(const std::string& path, const TerrainPackage& terrain,
                                      const std::string& terrain_path) {
  AnalysisPackage a = open_analysis_package(path);
  check_same_tiling(terrain.tiling, terrain_path, a.tiling, path);
  if (a.block_size != terrain.block_size)
    throw InputError(path + ": blocks of " + std::to_string(a.block_size) +
                     " samples, the terrain's (" + terrain_path + ") have " +
                     std::to_string(terrain.block_size) +
                     "; run globe-tiler analyze on this terrain package");
  AnalysisOverlay o;
  o.source.path = path;
  o.source.reader = std::move(a.reader);
  o.layers = a.meta.layers;
  return o;
}

std::string shading_needs(const ShadingSettings& s, const std::optional<std::string>& path,
                          const std::vector<AnalysisLayer>& layers) {
  std::vector<std::pair<AnalysisLayer, std::string>> need;
  const ShadingMode& mode = shading_mode(s.mode);
  if (mode.needs) need.emplace_back(*mode.needs, std::string("--shading ") + mode.name);
  if (s.lens_radius > 0)
    if (const ShadingMode& lens = shading_mode(s.lens_mode); lens.needs)
      need.emplace_back(*lens.needs, std::string("--lens ...:") + lens.name);
  if (s.ambient_occlusion) need.emplace_back(AnalysisLayer::kSkyview, "--ambient-occlusion");
  if (s.isoline_interval > 0 && s.isolines_of == ShadingSettings::IsolinesOf::kFlow)
    need.emplace_back(AnalysisLayer::kFlowAccumulation, "--isolines-of flow");
  for (const auto& [layer, what] : need) {
    const std::string name = tileformat::analysis_layer_info(layer).name;
    const std::string make = layer == AnalysisLayer::kPlanCurvature      ? "curvature"
                             : layer == AnalysisLayer::kFlowAccumulation ? "flow"
                                                                         : name;
    if (!path)
      return what + " draws the " + name +
             " layer of an analysis package: give one (globe-tiler analyze TERRAIN --layers " +
             make + " -o ANALYSIS.mbtiles)";
    if (std::find(layers.begin(), layers.end(), layer) == layers.end())
      return what + ": " + *path + " has no " + name +
             " layer; rebuild it with globe-tiler analyze --layers ...," + make;
  }
  return "";
}

}  // namespace globe::viewer
