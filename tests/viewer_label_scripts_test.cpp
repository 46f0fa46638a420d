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
