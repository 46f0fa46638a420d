// The shading modes' table (see shading_modes.hpp).
#include "render/shading_modes.hpp"

#include <stdexcept>

namespace globe::viewer {
namespace {

using tileformat::AnalysisLayer;

constexpr ShadingMode kModes[] = {
    {Shading::kHillshade, "hillshade", '1', "default; imagery is lit by it", std::nullopt,
     RampDomain::kHeights, 0, 0, "MODE_HILLSHADE"},
    {Shading::kElevation, "elevation", '2', "heights through the colour ramp, lit", std::nullopt,
     RampDomain::kHeights, 0, 0, "MODE_ELEVATION"},
    {Shading::kSlope, "slope", '3', "from an analysis package when given, else from the heights",
     std::nullopt, RampDomain::kFixed, 0, 90, "MODE_SLOPE"},
    {Shading::kAspect, "aspect", '4', "likewise", std::nullopt, RampDomain::kFixed, 0, 360,
     "MODE_ASPECT"},
    {Shading::kSkyview, "skyview", '5', "sky-view factor", AnalysisLayer::kSkyview,
     RampDomain::kFixed, 0, 1, "MODE_SKYVIEW"},
    {Shading::kEdges, "edges", '6', "ridges and valleys from plan curvature",
     AnalysisLayer::kPlanCurvature, RampDomain::kFixed, -1, 1, "MODE_EDGES"},
    {Shading::kFlow, "flow", '7', "rivers by upstream area, log scale",
     AnalysisLayer::kFlowAccumulation, RampDomain::kFlowLog2, 0, 0, "MODE_FLOW"},
};

}  // namespace

std::span<const ShadingMode> shading_modes() {
  return kModes;
}

const ShadingMode& shading_mode(Shading id) {
  for (const ShadingMode& m : kModes)
    if (m.id == id) return m;
  throw std::logic_error("shading mode without a row in shading_modes.cpp");
}

const ShadingMode* find_shading_mode(std::string_view name) {
  for (const ShadingMode& m : kModes)
    if (name == m.name) return &m;
  return nullptr;
}

const ShadingMode* shading_mode_for_key(int key) {
  for (const ShadingMode& m : kModes)
    if (key == m.key) return &m;
  return nullptr;
}

std::string shading_mode_defines() {
  std::string out;
  for (const ShadingMode& m : kModes)
    out += std::string("#define ") + m.glsl + " " + std::to_string(int(m.id)) + "\n";
  return out;
}

std::string with_shading_defines(const std::string& shader) {
  const size_t eol = shader.find('\n');
  if (shader.rfind("#version", 0) != 0 || eol == std::string::npos)
    throw std::logic_error("a shader without its #version line");
  return shader.substr(0, eol + 1) + shading_mode_defines() + shader.substr(eol + 1);
}

}  // namespace globe::viewer
