// Typed package metadata (lib/tileformat metadata.hpp) and the JSON reader
// under it: every kind round-trips through its keys, bad keys are format
// errors naming them, and the JSON reader follows RFC 8259.
#include <gtest/gtest.h>

#include <set>
#include <utility>

#include "tileformat/error.hpp"
#include "tileformat/json.hpp"
#include "tileformat/metadata.hpp"
#include "tileformat/package_kinds.hpp"

using namespace tileformat;

namespace {

CommonMetadata sample_common(const std::string& format) {
  CommonMetadata c;
  c.name = "area";
  c.format = format;
  c.type = "baselayer";
  c.description = build_description("Terrain", "globe-tiler", {{"dir/a.tif", 10}, {"b.tif", 20}});
  c.lonlat = {-180.00000000000003, -86.0, 180.00000000000003, 40.5};
  c.min_zoom = 2;
  c.max_zoom = 9;
  c.center_zoom = 9;
  c.tiling = Tiling::webmercator();
  c.generator = "globe-tiler 0.1.0";
  c.command_line = "globe-tiler terrain a.tif -o area.mbtiles";
  c.inputs = {{"dir/a \"quoted\".tif", 10}, {"b.tif", 20}};
  c.left_out = "latitudes -90..-85.05113";
  return c;
}

TEST(Metadata, TerrainRoundTripsAndClampsBoundsToTheTiling) {
  TerrainMetadata m;
  m.common = sample_common(kMBlockFormat);
  m.resampling = "bilinear";
  m.block_size = 257;
  m.lattice = 16;
  m.height_step = 0.01;
  m.fill_height = -10.5;
  const MetadataMap keys = to_metadata(m);
  EXPECT_EQ(keys.at("description"), "Terrain built by globe-tiler from a.tif and 1 more");
  // -85.05112878 (10 digits) would be past the limit: the exact limit is written.
  EXPECT_EQ(keys.at("bounds"), "-180,-85.05112877980659,180,40.5");
  EXPECT_EQ(keys.at("center"), "0,-22.27556439,9");
  EXPECT_EQ(keys.at("globe:scheme"), "webmercator");
  const TerrainMetadata back = read_terrain_metadata(keys);
  EXPECT_EQ(back.block_size, 257);
  EXPECT_EQ(back.lattice, 16);
  EXPECT_DOUBLE_EQ(back.height_step, 0.01);
  EXPECT_DOUBLE_EQ(back.fill_height, -10.5);
  EXPECT_EQ(back.common.tiling.scheme, Scheme::kWebMercator);
  EXPECT_TRUE(back.common.has_bounds);
  EXPECT_DOUBLE_EQ(back.common.lonlat.min_x, -180);
  EXPECT_EQ(back.common.center_zoom, 9);
  ASSERT_EQ(back.common.inputs.size(), 2u);
  EXPECT_EQ(back.common.inputs[0].name, "dir/a \"quoted\".tif");
  EXPECT_EQ(back.common.inputs[1].bytes, 20u);
  EXPECT_EQ(back.common.left_out, m.common.left_out);
  EXPECT_EQ(to_metadata(back), keys);  // a read package writes the same keys
}

TEST(Metadata, ImageAndLinesRoundTrip) {
  ImageMetadata im;
  im.common = sample_common("jpg");
  im.format = ImageFormat::kJpeg;
  im.tile_size = 512;
  im.colour_bands = 1;
  im.quality = 85;
  im.scale = std::make_pair(-5.5, 1200.0);
  const ImageMetadata ib = read_image_metadata(to_metadata(im));
  EXPECT_EQ(ib.format, ImageFormat::kJpeg);
  EXPECT_EQ(ib.tile_size, 512);
  EXPECT_EQ(ib.colour_bands, 1);
  EXPECT_EQ(ib.quality, 85);
  EXPECT_FALSE(ib.png_level.has_value());
  ASSERT_TRUE(ib.scale.has_value());
  EXPECT_DOUBLE_EQ(ib.scale->first, -5.5);

  LineMetadata lm;
  lm.common = sample_common(kLineClustersFormat);
  lm.extent = 4096;
  lm.cluster_grid = 16;
  lm.simplify_px = 0.25;
  lm.tile_px = 256;
  lm.features = 7;
  lm.classes_json = R"([{"id":0,"name":"roads"}])";
  lm.layers = {{"roads", "roads.shp", 7}};
  const LineMetadata lb = read_line_metadata(to_metadata(lm));
  EXPECT_EQ(lb.extent, 4096);
  EXPECT_EQ(lb.cluster_grid, 16);
  EXPECT_DOUBLE_EQ(lb.simplify_px, 0.25);
  EXPECT_EQ(lb.features, 7u);
  EXPECT_EQ(lb.classes_json, lm.classes_json);
  ASSERT_EQ(lb.layers.size(), 1u);
  EXPECT_EQ(lb.layers[0].source, "roads.shp");
}

TEST(Metadata, OtherToolsMBTilesReadAsWebMercatorWithoutTileFacts) {
  const ImageMetadata m =
      read_image_metadata({{"format", "png"}, {"minzoom", "0"}, {"maxzoom", "3"}});
  EXPECT_FALSE(m.common.has_tiling);
  EXPECT_FALSE(m.common.has_bounds);
  EXPECT_EQ(m.common.tiling.scheme, Scheme::kWebMercator);
  EXPECT_EQ(m.tile_size, 0);
}

TEST(Metadata, BadKeysAreFormatErrorsNamingThem) {
  TerrainMetadata m;
  m.common = sample_common(kMBlockFormat);
  m.block_size = 257;
  m.lattice = 16;
  m.height_step = 1;
  auto expect_error = [](const MetadataMap& keys, const std::string& what) {
    try {
      read_terrain_metadata(keys);
      ADD_FAILURE() << "no error for " << what;
    } catch (const FormatError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  MetadataMap keys = to_metadata(m);
  keys.erase("globe:block_size");
  expect_error(keys, "globe:block_size is missing");
  keys = to_metadata(m);
  keys["globe:height_step"] = "one";
  expect_error(keys, "globe:height_step is not a number");
  keys = to_metadata(m);
  keys["globe:scheme"] = "mercator";
  expect_error(keys, "globe:scheme 'mercator'");
  keys = to_metadata(m);
  keys["globe:inputs"] = "[{\"name\":\"a\"}";
  expect_error(keys, "globe:inputs is not valid JSON");
  keys = to_metadata(m);
  keys.erase("globe:scheme");
  expect_error(keys, "globe:scheme is missing");
}

// The sky view's radius per zoom (globe:skyview_radius_by_zoom) round-trips,
// is absent from packages made before it, and a malformed list is an error
// naming the key.
TEST(Metadata, AnalysisSkyviewRadiusByZoom) {
  AnalysisMetadata m;
  m.common = sample_common(kAnalysisFormat);
  m.block_size = 257;
  m.layers = {AnalysisLayer::kSkyview};
  m.terrain = "t.mbtiles";
  m.height_step = 0.01;
  m.skyview_directions = 16;
  m.skyview_radius_m = 10000;
  m.skyview_radius_by_zoom = {{2, 7620}, {3, 10000}};
  MetadataMap keys = to_metadata(m);
  EXPECT_EQ(keys["globe:skyview_radius_by_zoom"], "2:7620,3:10000");
  const AnalysisMetadata back = read_analysis_metadata(keys);
  EXPECT_EQ(back.skyview_radius_by_zoom, m.skyview_radius_by_zoom);
  keys.erase("globe:skyview_radius_by_zoom");
  EXPECT_TRUE(read_analysis_metadata(keys).skyview_radius_by_zoom.empty());
  for (const char* bad : {"3", "3:", ":10", "a:10", "3:ten", "3:10,", "3:-1", "99:10", "3:10 "}) {
    keys["globe:skyview_radius_by_zoom"] = bad;
    try {
      read_analysis_metadata(keys);
      ADD_FAILURE() << "no error for '" << bad << "'";
    } catch (const FormatError& e) {
      EXPECT_NE(std::string(e.what()).find("globe:skyview_radius_by_zoom"), std::string::npos)
          << e.what();
    }
  }
}

TEST(Metadata, PackageKindFollowsFormat) {
  EXPECT_EQ(package_kind_of_format(kMBlockFormat), PackageKind::kTerrain);
  EXPECT_EQ(package_kind_of_format(kLineClustersFormat), PackageKind::kLines);
  EXPECT_EQ(package_kind_of_format("webp"), PackageKind::kImage);
  EXPECT_FALSE(package_kind_of_format("pbf").has_value());
}

// One descriptor per kind, in PackageKind order, each naming the tool that
// inspects it and the command that makes it; each own format is recognised
// as its kind and no other.
TEST(Metadata, EveryKindHasOneDescriptor) {
  const std::pair<PackageKind, const char*> formats[] = {
      {PackageKind::kTerrain, kMBlockFormat},     {PackageKind::kImage, "png"},
      {PackageKind::kLines, kLineClustersFormat}, {PackageKind::kAnalysis, kAnalysisFormat},
      {PackageKind::kPoints, kPointsFormat},      {PackageKind::kAreas, kAreasFormat}};
  ASSERT_EQ(package_kinds().size(), std::size(formats));
  std::set<std::string> names, keys;
  for (size_t i = 0; i < package_kinds().size(); ++i) {
    const PackageKindDescriptor& d = package_kinds()[i];
    EXPECT_EQ(static_cast<size_t>(d.kind), i);
    EXPECT_EQ(&describe(d.kind), &d);
    EXPECT_TRUE(names.insert(d.name).second) << d.name;
    EXPECT_TRUE(keys.insert(d.info_key).second) << d.info_key;
    EXPECT_TRUE(std::string(d.tool) == "globe-tiler" || std::string(d.tool) == "globe-vectorize");
    EXPECT_EQ(std::string(d.maker).rfind(d.tool, 0), 0u) << d.maker;
    EXPECT_NE(std::string(d.extract).find(std::string(d.tool) + " extract"), std::string::npos);
    EXPECT_EQ(package_kind_name(d.kind), std::string(d.name));
  }
  for (const auto& [kind, format] : formats) {
    EXPECT_EQ(package_kind_of_format(format), kind) << format;
    for (const PackageKindDescriptor& d : package_kinds())
      EXPECT_EQ(is_format_of(d, format), d.kind == kind) << d.name << " " << format;
  }
}

TEST(Json, ReadsEveryValueKindAndEscape) {
  const JsonValue v = JsonValue::parse(
      R"( {"a": [1, -2.5e3, 0, true, false, null], "s": "q\"\\\/\b\f\n\r\t\u00e9\ud83d\ude00", "o": {}} )");
  ASSERT_TRUE(v.is_object());
  const auto& a = v.find("a")->array();
  ASSERT_EQ(a.size(), 6u);
  EXPECT_EQ(a[0].number(), 1);
  EXPECT_EQ(a[1].number(), -2500);
  EXPECT_TRUE(a[3].boolean());
  EXPECT_FALSE(a[4].boolean());
  EXPECT_TRUE(a[5].is_null());
  EXPECT_EQ(v.find("s")->string(), "q\"\\/\b\f\n\r\t\xC3\xA9\xF0\x9F\x98\x80");
  EXPECT_TRUE(v.find("o")->members().empty());
  EXPECT_EQ(v.find("missing"), nullptr);
  EXPECT_EQ(JsonValue::parse(R"({"k":1,"k":2})").find("k")->number(), 2);  // the last wins
}

TEST(Json, RejectsWhatRfc8259Rejects) {
  for (const char* bad : {"", "[1,]", "{\"a\" 1}", "[01]", "[1.]", "[-]", "\"a", "\"\\x\"",
                          "\"\\ud800\"", "[1] x", "{a:1}", "tru", "\"tab\there\"", "[1e]"}) {
    EXPECT_THROW(JsonValue::parse(bad), JsonError) << bad;
  }
  EXPECT_THROW(JsonValue::parse(std::string(100000, '[')), JsonError);  // deep, not a crash
  try {
    JsonValue::parse("{\n  \"a\": ?}");
    ADD_FAILURE();
  } catch (const JsonError& e) {
    EXPECT_STREQ(e.what(), "line 2, column 8: unexpected character '?'");
  }
  EXPECT_THROW(JsonValue::parse("1").string(), JsonError);
}

TEST(Json, EscapeRoundTrips) {
  const std::string s = "a\"b\\c\n\x01 é";
  EXPECT_EQ(JsonValue::parse("\"" + json_escape(s) + "\"").string(), s);
}

}  // namespace
