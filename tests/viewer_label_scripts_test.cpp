// Labels in many scripts, as the viewer draws them (docs/labels.md "Text"):
// places named in Latin with diacritics, Greek, Cyrillic, Arabic (joined,
// right to left), Hebrew and Devanagari (conjuncts), drawn without terrain
// on the flat frame, against tests/data/render/label_scripts.png (the
// shaping itself is checked against hb-shape in tests/text_test.cpp). And
// the JSON record names each label with its text as stored.
#include <gtest/gtest.h>

#include <fstream>

#include "render_fixtures.hpp"
#include "test_support.hpp"
#include "tileformat/json.hpp"

using namespace globe_test;

TEST(ViewerLabelScripts, EveryScriptDrawsAsExpected) {
  TempDir dir;
  const std::string csv = (dir / "places.csv").string();
  std::ofstream(csv) << "name,lon,lat,v\n"
                        "Zürich,0.0,0.0,9\n"
                        "Αθήνα,1.0,0.6,8\n"
                        "Москва,2.0,0.0,7\n"
                        "القاهرة,0.0,-0.8,6\n"
                        "ירושלים,1.1,-0.4,5\n"
                        "नई दिल्ली,2.1,-0.9,4\n";
  const std::string pkg = (dir / "places.mbtiles").string();
  RunResult r = run(vectorize() + " points -q " + csv +
                        " --xy lon,lat --fields v --label-field name --merge-px 0 -o " + pkg,
                    dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string out = (dir / "scripts.png").string(), json = (dir / "l.json").string();
  r = run(viewer() + " " + pkg +
              " --flat --size 320x180 --camera=1.2,-0.1,300000,0,0 --label-size 16 --snapshot " +
              out + " --labels-json " + json,
          dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const tileformat::JsonValue j = tileformat::JsonValue::parse(read_file(json));
  std::set<std::string> drawn;
  for (const tileformat::JsonValue& l : j.find("frames")->array().at(0).find("labels")->array())
    drawn.insert(l.find("text")->string());
  for (const char* name : {"Zürich", "Αθήνα", "Москва", "القاهرة", "ירושלים", "नई दिल्ली"})
    EXPECT_EQ(drawn.count(name), 1u) << name << " not drawn";
  expect_image(out, "label_scripts");
}

// --labels FIELD shows another attribute of the labelled features (their
// ISO codes instead of the stored long names), --labels off none.
TEST(ViewerLabelScripts, LabelsFieldAndOff) {
  TempDir dir;
  const std::string pkg = (dir / "w.mbtiles").string();
  RunResult r = run(vectorize() + " areas -q " + sample("world.gpkg").string() +
                        " --label-field name_long --tiling geodetic -o " + pkg,
                    dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto texts = [&](const std::string& option) {
    const std::string json = (dir / "l.json").string();
    const RunResult v = run(viewer() + " " + pkg + " --size 320x180 --camera=10,48,4000000,0,0 " +
                                option + " --labels-json " + json,
                            dir.path());
    EXPECT_EQ(v.exit_code, 0) << v.err;
    std::set<std::string> out;
    const tileformat::JsonValue j = tileformat::JsonValue::parse(read_file(json));
    for (const tileformat::JsonValue& l : j.find("frames")->array().at(0).find("labels")->array())
      out.insert(l.find("text")->string());
    return out;
  };
  const std::set<std::string> names = texts(""), codes = texts("--labels iso_a2");
  EXPECT_TRUE(names.count("Germany") || names.count("France")) << names.size();
  EXPECT_TRUE(codes.count("DE") || codes.count("FR")) << codes.size();
  for (const std::string& c : codes)
    EXPECT_EQ(c.size(), 2u) << c;
  EXPECT_TRUE(texts("--labels off").empty());
}

// A --label-font that cannot be read is an input error naming the file (exit
// 1), and no picture is written under the snapshot's name.
TEST(ViewerLabelScripts, AnUnreadableFontNamesItself) {
  TempDir dir;
  const std::string pkg = (dir / "w.mbtiles").string(), out = (dir / "x.png").string();
  RunResult r = run(vectorize() + " areas -q " + sample("world.gpkg").string() +
                        " --label-field name_long -o " + pkg,
                    dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run(viewer() + " " + pkg + " --size 160x90 --label-font " + (dir / "no.ttf").string() +
              " --snapshot " + out,
          dir.path());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("no.ttf"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--label-font"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}
