// The analysis package drawn with a terrain (`globe-view TERRAIN ANALYSIS`):
// opened, checked against the terrain's tiling and block size, and against
// the layers the shading draws from it (sky view, edges, ambient occlusion
// need it; slope and aspect use it when it has them).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "data/block_cache.hpp"
#include "render/terrain_renderer.hpp"
#include "runtime/terrain_package.hpp"
#include "tileformat/analysis_block.hpp"

namespace globe::viewer {

struct AnalysisOverlay {
  AnalysisSource source;
  std::vector<tileformat::AnalysisLayer> layers;  // what the package holds
};

// Throws InputError (not an analysis package, another tiling or block size).
AnalysisOverlay open_analysis_overlay(const std::string& path, const TerrainPackage& terrain,
                                      const std::string& terrain_path);

// "" when `shading` can be drawn with the analysis package `path` holding
// `layers` (no path: none given); else what is missing and how to make it.
std::string shading_needs(const ShadingSettings& shading, const std::optional<std::string>& path,
                          const std::vector<tileformat::AnalysisLayer>& layers);

}  // namespace globe::viewer
