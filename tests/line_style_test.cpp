// Line styles in JSON: globe:classes as the package stores it, and style
// files over it (the viewer's --style).
#include <gtest/gtest.h>

#include "runtime/errors.hpp"
#include "runtime/line_style.hpp"

namespace {

using globe::NamedLineStyle;

const char* kClasses =
    R"([{"id":0,"name":"road","layer":"l","features":3,"color":"","width":1.5,"unit":"px",)"
    R"("casing_color":"","casing_width":0,"dash":[]},)"
    R"({"id":1,"name":"river","layer":"l","features":1,"color":"#0000ff","width":20,"unit":"m",)"
    R"("casing_color":"#000000","casing_width":2,"dash":[6,3]}])";

TEST(LineStyle, ClassesJsonRoundTripsWithPaletteDefaults) {
  const auto c = globe::parse_classes_json(kClasses, "pkg");
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].name, "road");
  EXPECT_EQ(c[0].style.color, globe::palette_color(0));
  EXPECT_TRUE(c[1].style.width_in_m);
  EXPECT_EQ(c[1].style.casing_color, "#000000");
  EXPECT_EQ(c[1].style.dash, (std::vector<double>{6, 3}));
}

TEST(LineStyle, StyleFileOverridesNamedClassesAndStarTheRest) {
  auto c = globe::parse_classes_json(kClasses, "pkg");
  globe::apply_style_json(
      R"({"river": {"width": 3, "unit": "px", "dash": []}, "*": {"color": "#ff0000", "visible": false}})",
      "s.json", c);
  EXPECT_EQ(c[0].style.color, "#ff0000");
  EXPECT_FALSE(c[0].style.visible);
  EXPECT_EQ(c[1].style.color, "#0000ff");  // named: "*" does not apply
  EXPECT_TRUE(c[1].style.visible);
  EXPECT_FALSE(c[1].style.width_in_m);
  EXPECT_EQ(c[1].style.width, 3);
  EXPECT_TRUE(c[1].style.dash.empty());
}

TEST(LineStyle, BadStyleFilesNameTheProblem) {
  const std::pair<const char*, const char*> cases[] = {
      {"{", "not valid JSON"},
      {"[]", "expected a JSON object"},
      {R"({"lake": {}})", "no class \"lake\""},
      {R"({"road": {"colour": "#ff0000"}})", "unknown key"},
      {R"({"road": {"color": "red"}})", "is not #rrggbb"},
      {R"({"road": {"width": -1}})", "out of range"},
      {R"({"road": {"dash": [1, 2, 3]}})", "on/off pairs"},
      {R"({"road": {"unit": "ft"}})", "not px or m"},
  };
  for (const auto& [json, message] : cases) {
    auto c = globe::parse_classes_json(kClasses, "pkg");
    try {
      globe::apply_style_json(json, "s.json", c);
      ADD_FAILURE() << json << " was accepted";
    } catch (const globe::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << json << ": " << e.what();
      EXPECT_NE(std::string(e.what()).find("s.json"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
