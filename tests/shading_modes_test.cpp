// The shading modes' table (render/shading_modes.hpp): every mode has one
// row with a unique name and key, the terrain shader has a branch for each,
// and --help, parsing and the window keys are made from it.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "app/viewer_settings.hpp"
#include "render/shading_modes.hpp"
#include "render/terrain_shaders.hpp"

namespace {

using namespace globe::viewer;

TEST(ShadingModes, OneRowPerModeWithUniqueNamesAndKeys) {
  std::set<std::string> names;
  std::set<int> ids, keys;
  for (const ShadingMode& m : shading_modes()) {
    EXPECT_TRUE(names.insert(m.name).second) << m.name;
    EXPECT_TRUE(ids.insert(int(m.id)).second) << m.name;
    EXPECT_TRUE(keys.insert(m.key).second) << m.name;
    EXPECT_EQ(&shading_mode(m.id), &m);
    EXPECT_EQ(find_shading_mode(m.name), &m);
    EXPECT_EQ(shading_mode_for_key(m.key), &m);
  }
  // The enum's values 0..N-1 all have rows (kFlow is the last).
  EXPECT_EQ(ids.size(), size_t(Shading::kFlow) + 1);
  EXPECT_EQ(find_shading_mode("imagery"), nullptr);  // a flag, not a mode
  EXPECT_EQ(shading_mode_for_key('9'), nullptr);
}

TEST(ShadingModes, TheShaderHasABranchForEachMode) {
  const std::string shader = with_shading_defines(shaders::kTerrainFragment);
  for (const ShadingMode& m : shading_modes()) {
    const std::string define = std::string("#define ") + m.glsl + " " + std::to_string(int(m.id));
    EXPECT_NE(shader.find(define), std::string::npos) << m.name;
    // The branch: a test of the mode drawn (u_mode, or the lens's inside it), or
    // the final else marked with the name.
    EXPECT_TRUE(shader.find(std::string("mode == ") + m.glsl) != std::string::npos ||
                shader.find(std::string("else {  // ") + m.glsl) != std::string::npos)
        << m.name << " has no branch in terrain_shaders.hpp";
  }
  EXPECT_EQ(shader.rfind("#version 450 core\n#define", 0), 0u);
}

TEST(ShadingModes, ParsingAndHelpComeFromTheTable) {
  for (const ShadingMode& m : shading_modes()) {
    const auto s = parse_viewer_settings({"globe-view", "--shading", m.name, "t.mbtiles"});
    ASSERT_TRUE(s.has_value()) << m.name;
    EXPECT_EQ(s->shading.mode, m.id);
  }
  EXPECT_THROW(parse_viewer_settings({"globe-view", "--shading", "curvature", "t.mbtiles"}),
               std::exception);
}

}  // namespace
