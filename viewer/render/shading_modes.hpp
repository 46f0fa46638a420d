// The terrain's shading modes, one row each (docs/architecture.md "How to
// add a shading mode"): the --shading name and help, the window key, the
// analysis layer the mode draws, the domain of its colour ramp and the name
// its branch of the terrain shader tests. --help, option parsing, window
// keys, the analysis checks, the ramp and the shader's defines are all made
// from this table; the shader's branch itself lives in terrain_shaders.hpp.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "tileformat/analysis_block.hpp"

namespace globe::viewer {

// Slope and aspect come from an analysis package when one is drawn (else
// from the drawn heights, per pixel); sky view, edges and flow need one.
enum class Shading {
  kHillshade,
  kElevation,
  kSlope,
  kAspect,
  kSkyview,  // the sky-view factor, white on open ground
  kEdges,    // hillshade with ridges warm and valleys blue (plan curvature)
  kFlow,     // hillshade with rivers blue by upstream area, on a log scale
};

// What a mode's colour ramp (--colormap, the elevation ramp) spans.
enum class RampDomain {
  kHeights,   // the data's heights (percentiles or --height-range)
  kFixed,     // lo .. hi
  kFlowLog2,  // log2 upstream area: the 16 doublings below the largest loaded
};

struct ShadingMode {
  Shading id;
  const char* name;                                // --shading NAME
  char key;                                        // the window key that selects it
  const char* help;                                // a note for --help after the name
  std::optional<tileformat::AnalysisLayer> needs;  // the analysis layer it draws
  RampDomain ramp;
  double lo, hi;     // kFixed's domain
  const char* glsl;  // the shader's name for it (MODE_...)
};

std::span<const ShadingMode> shading_modes();
const ShadingMode& shading_mode(Shading id);
const ShadingMode* find_shading_mode(std::string_view name);
const ShadingMode* shading_mode_for_key(int key);  // GLFW key codes of digits are ASCII

// "#define MODE_HILLSHADE 0" ... for the terrain shader.
std::string shading_mode_defines();
// The shader source with the defines after its #version line.
std::string with_shading_defines(const std::string& shader);

}  // namespace globe::viewer
