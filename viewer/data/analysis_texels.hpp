// What the terrain pass reads from an analysis package (tileformat §9), per
// block sample, as four floats: r the sky-view factor, g the plan curvature
// (1/m, ridges > 0), (b, a) the downhill gradient tan(slope) * (sin, cos) of
// the aspect — a vector, so it interpolates across 0/360 degrees and gives
// slope and aspect back. Where the package has no value or no such layer:
// sky view 1, curvature 0, gradient (0, 0). Pure conversion; runs on the
// loader thread.
#pragma once

#include <vector>

#include "tileformat/analysis_block.hpp"

namespace globe::viewer {

// size*size*4 floats, row-major from the north row.
std::vector<float> analysis_texels(const tileformat::AnalysisBlock& block);

// The flow shading's texels, three floats a sample: log2 of the upstream
// area in m^2 (kNoFlow where the package has none, or no flow_accumulation
// layer), then the D8 step downstream in samples (x east, y south; (0, 0)
// at outlets or without a flow_direction layer).
inline constexpr float kNoFlow = -100;
inline constexpr int kFlowTexel = 3;
std::vector<float> flow_texels(const tileformat::AnalysisBlock& block);

}  // namespace globe::viewer
