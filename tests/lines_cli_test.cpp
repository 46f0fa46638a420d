// globe-vectorize on synthetic inputs: a valid package, the geometry round
// trip through `extract`, determinism (threads, spilling), classes and
// styles, the antimeridian, and bad input (clear error, nothing written).
#include <gtest/gtest.h>

#include <cmath>

#include "line_fixtures.hpp"
#include "raster_fixtures.hpp"
#include "test_support.hpp"
#include "tileformat/line_tile.hpp"
#include "tileformat/package.hpp"
#include "tileformat/sqlite_db.hpp"

namespace {

using namespace globe_test;

std::string coords(const std::vector<globe::XY>& pts) {
  std::string s = "[";
  for (size_t i = 0; i < pts.size(); ++i) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s[%.7f,%.7f]", i ? "," : "", pts[i].x, pts[i].y);
    s += buf;
  }
  return s + "]";
}

std::string feature(int fid, const std::string& kind, const std::string& geometry) {
  return "{\"type\":\"Feature\",\"properties\":{\"fid\":" + std::to_string(fid) + ",\"kind\":\"" +
         kind + "\"},\"geometry\":" + geometry + "}";
}

// Wiggly lines near Bern, a polygon with a hole, a multi-line, a point, and
// two features without usable geometry (one repeated point, an empty line).
std::string synthetic_geojson() {
  std::vector<std::string> f;
  for (int k = 0; k < 3; ++k) {
    std::vector<globe::XY> pts;
    for (int i = 0; i <= 400; ++i)
      pts.push_back({7.3 + i * 0.0008, 46.9 + 0.01 * k + 0.004 * std::sin(i / 7.0 + k)});
    f.push_back(feature(k + 1, k ? "b" : "a",
                        "{\"type\":\"LineString\",\"coordinates\":" + coords(pts) + "}"));
  }
  f.push_back(
      feature(4, "b",
              "{\"type\":\"Polygon\",\"coordinates\":[" +
                  coords({{7.35, 46.95}, {7.5, 46.95}, {7.5, 47.0}, {7.35, 47.0}, {7.35, 46.95}}) +
                  "," + coords({{7.4, 46.96}, {7.45, 46.96}, {7.45, 46.98}, {7.4, 46.96}}) + "]}"));
  f.push_back(feature(5, "a",
                      "{\"type\":\"MultiLineString\",\"coordinates\":[" +
                          coords({{7.31, 46.88}, {7.6, 46.89}}) + "," +
                          coords({{7.32, 46.87}, {7.33, 46.99}, {7.36, 46.87}}) + "]}"));
  f.push_back(feature(6, "a", "{\"type\":\"Point\",\"coordinates\":[7.44,46.95]}"));
  f.push_back(feature(7, "a",
                      "{\"type\":\"LineString\",\"coordinates\":" +
                          coords({{7.4, 46.9}, {7.4, 46.9}, {7.4, 46.9}}) + "}"));
  f.push_back(feature(8, "a", "{\"type\":\"LineString\",\"coordinates\":[]}"));
  std::string out = "{\"type\":\"FeatureCollection\",\"features\":[";
  for (size_t i = 0; i < f.size(); ++i)
    out += (i ? "," : "") + f[i];
  return out + "]}";
}

class LinesCli : public ::testing::Test {
 protected:
  void SetUp() override {
    input_ = (dir_ / "lines.geojson").string();
    write_text(input_, synthetic_geojson());
  }
  RunResult vectorize(const std::string& args) {
    return run(globe_test::vectorize() + " " + args, dir_.path());
  }
  std::string pkg(const std::string& name) { return (dir_ / name).string(); }
  TempDir dir_;
  std::string input_;
};

TEST_F(LinesCli, BuildsAValidPackageAndCountsWhatItSkips) {
  auto r = vectorize("lines " + input_ + " -o " + pkg("a.mbtiles") + " --max-zoom 12");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("6 features (2 skipped"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("13 points"), std::string::npos) << r.err;  // one per zoom 0..12
  r = vectorize("validate " + pkg("a.mbtiles"));
  EXPECT_EQ(r.exit_code, 0) << r.out;
  r = vectorize("info " + pkg("a.mbtiles"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("application/vnd.globe.lineclusters"), std::string::npos);
  EXPECT_NE(r.out.find("features: 6"), std::string::npos) << r.out;
  tileformat::PackageReader reader(pkg("a.mbtiles"));
  EXPECT_EQ(reader.meta("maxzoom"), "12");
  EXPECT_EQ(reader.meta("globe:scheme"), "webmercator");
  // Attributes are kept per feature.
  tileformat::SqliteDb db(pkg("a.mbtiles"), tileformat::SqliteDb::Mode::kReadOnly);
  auto props =
      db.query_int("SELECT count(*) FROM features WHERE properties LIKE '%\"kind\":\"b\"%'");
  EXPECT_EQ(props, 3);
  EXPECT_FALSE(fs::exists(pkg("a.mbtiles.tmp")));
  EXPECT_FALSE(fs::exists(pkg("a.mbtiles.scratch-geometry")));
}

// A GeoPackage QGIS has touched: beside its layers a layer_styles table
// without geometry (made here with ogr2ogr, as QGIS stores it). The table is
// left out with a note; naming it with --layer is an error naming it.
TEST_F(LinesCli, GeoPackageTablesWithoutGeometryAreLeftOut) {
  const std::string gpkg = pkg("qgis.gpkg");
  write_text((dir_ / "styles.csv").string(),
             "f_table_name,styleName,styleQML\nroads,default,<qml/>\n");
  ASSERT_TRUE(run_all({"ogr2ogr -f GPKG " + gpkg + " " + input_ + " -nln roads",
                       "ogr2ogr -update -f GPKG " + gpkg + " " + (dir_ / "styles.csv").string() +
                           " -nln layer_styles"},
                      dir_.path()));
  auto r = vectorize("lines " + gpkg + " -o " + pkg("q.mbtiles") + " --max-zoom 8");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("layer 'layer_styles': no geometry"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("6 features"), std::string::npos) << r.err;
  r = vectorize("lines " + gpkg + " --layer layer_styles -o " + pkg("t.mbtiles"));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("layer 'layer_styles': a table without geometry"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(pkg("t.mbtiles")));
}

// Extracted finest-zoom lines match the projected input within the
// quantization step plus the simplification tolerance, both ways.
TEST_F(LinesCli, ExtractedLinesMatchTheInputWithinTolerance) {
  ASSERT_EQ(vectorize("lines " + input_ + " -o " + pkg("a.mbtiles") + " --max-zoom 13").exit_code,
            0);
  auto r = vectorize("extract " + pkg("a.mbtiles") + " --zoom 13 -o " + pkg("z13.gpkg"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto input = read_lines(input_, "", "fid", "EPSG:3857");
  // feature ids in the package follow input order of the kept features (1..6 here).
  const auto extracted = read_lines(pkg("z13.gpkg"), "lines", "feature_id");
  const double tile = 40075016.685578488 / (1 << 13);
  const double tol = 0.25 * tile / 256 + tile / 4096 * 0.75 + 1e-6;
  int compared = 0;
  for (const auto& [id, lines] : input) {
    if (id > 5) continue;  // 6 is the point; 7, 8 have no usable geometry
    ASSERT_TRUE(extracted.count(id)) << "feature " << id << " missing";
    EXPECT_LE(directed_hausdorff(extracted.at(id), lines), tol) << "feature " << id;
    EXPECT_LE(directed_hausdorff(lines, extracted.at(id)), tol) << "feature " << id;
    ++compared;
  }
  EXPECT_EQ(compared, 5);
}

TEST_F(LinesCli, ThreadCountAndSpillingGiveIdenticalPackages) {
  // Enough lines that a 1 MB sort budget spills to disk.
  std::string json = "{\"type\":\"FeatureCollection\",\"features\":[";
  for (int k = 0; k < 150; ++k) {
    std::vector<globe::XY> pts;
    for (int i = 0; i <= 300; ++i)
      pts.push_back({7.0 + i * 0.002, 46.5 + 0.004 * k + 0.003 * std::sin(i / 5.0 + k)});
    json += (k ? "," : "") +
            feature(k + 1, "a", "{\"type\":\"LineString\",\"coordinates\":" + coords(pts) + "}");
  }
  write_text((dir_ / "many.geojson").string(), json + "]}");
  // Same command line in three folders (the command line is metadata).
  for (std::string run_name : {"j1", "j2", "spill"}) {
    fs::create_directories(dir_ / run_name);
    const std::string opts = run_name == "j1"   ? "-j1"
                             : run_name == "j2" ? "-j2"
                                                : "-j2 --memory-mb 1";
    auto r = run("cd " + pkg(run_name) + " && " + globe_test::vectorize() +
                     " lines ../many.geojson --max-zoom 14 -o p.mbtiles " + opts,
                 dir_.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    if (run_name == "spill") {
      EXPECT_NE(r.err.find("sorted on disk"), std::string::npos) << r.err;
    }
  }
  const std::string a = read_file(pkg("j1/p.mbtiles"));
  EXPECT_TRUE(a == read_file(pkg("j2/p.mbtiles"))) << "-j1 and -j2 packages differ";
  EXPECT_TRUE(a == read_file(pkg("spill/p.mbtiles"))) << "spilled and in-memory packages differ";
}

TEST_F(LinesCli, ClassFieldMapAndStylesReachTheMetadataAndTheGrid) {
  auto r = vectorize("lines " + input_ + " -o " + pkg("c.mbtiles") +
                     " --max-zoom 10 --class-field kind --class-map a=highway,b=path"
                     " --style highway:color=#ff0000,width=12px,casing=#000000@2px,dash=6+3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  tileformat::PackageReader reader(pkg("c.mbtiles"));
  const std::string classes = *reader.meta("globe:classes");
  EXPECT_NE(classes.find("\"name\":\"highway\""), std::string::npos) << classes;
  EXPECT_NE(classes.find("\"color\":\"#ff0000\",\"width\":12"), std::string::npos) << classes;
  EXPECT_NE(classes.find("\"dash\":[6,3]"), std::string::npos) << classes;
  EXPECT_NE(classes.find("\"name\":\"path\""), std::string::npos) << classes;
  // Reach = (12/2 + 2 casing + 1 antialiasing) px at 16 units per px.
  reader.for_each_tile([](tileformat::TileId, std::span<const uint8_t> blob) {
    EXPECT_EQ(tileformat::decode_line_tile(blob).reach, 144u);
  });
  for (const char* bad : {"--style highway:color=red", "--style highway:width=-1",
                          "--class-map novalue", "--style x:shade=1"}) {
    r = vectorize("lines " + input_ + " -o " + pkg("bad.mbtiles") + " " + std::string(bad));
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.err;
  }
}

TEST_F(LinesCli, LinesAcrossTheAntimeridianAreCutNotStretched) {
  const std::string path = (dir_ / "pacific.geojson").string();
  write_text(path,
             "{\"type\":\"FeatureCollection\",\"features\":[" +
                 feature(1, "a",
                         "{\"type\":\"LineString\",\"coordinates\":" +
                             coords({{170, -10}, {179, -12}, {-175, -15}, {-168, -16}}) + "}") +
                 "]}");
  auto r = vectorize("lines " + path + " -o " + pkg("p.mbtiles") + " --max-zoom 4");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("1 antimeridian cuts"), std::string::npos) << r.err;
  ASSERT_EQ(vectorize("extract " + pkg("p.mbtiles") + " --zoom 4 -o " + pkg("p.gpkg")).exit_code,
            0);
  double longest = 0, west = 1e30, east = -1e30;
  for (const auto& [id, lines] : read_lines(pkg("p.gpkg"), "lines", "feature_id"))
    for (const auto& l : lines)
      for (size_t i = 0; i < l.size(); ++i) {
        west = std::min(west, l[i].x);
        east = std::max(east, l[i].x);
        if (i) longest = std::max(longest, std::hypot(l[i].x - l[i - 1].x, l[i].y - l[i - 1].y));
      }
  EXPECT_LT(longest, 2e6);  // no segment across the whole map
  EXPECT_LT(west, -18e6);   // pieces at both edges of the world
  EXPECT_GT(east, 18e6);
}

TEST_F(LinesCli, BboxKeepsOnlyItsArea) {
  ASSERT_EQ(vectorize("lines " + input_ + " -o " + pkg("all.mbtiles") + " --max-zoom 12").exit_code,
            0);
  auto r = vectorize("lines " + input_ + " -o " + pkg("part.mbtiles") +
                     " --max-zoom 12 --bbox 7.3,46.85,7.4,46.95");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  tileformat::PackageReader all(pkg("all.mbtiles")), part(pkg("part.mbtiles"));
  EXPECT_LT(part.zoom_summaries().back().tiles, all.zoom_summaries().back().tiles);
  EXPECT_LE(part.zoom_summaries().back().max_x, all.zoom_summaries().back().max_x);
}

// --like: lines take a local terrain's tiling (CRS, origin, root), so both
// packages share tile ids and the lines land where they are in that CRS.
TEST_F(LinesCli, LikeAdoptsTheTilingOfALocalTerrainPackage) {
  const double gt[6] = {2600000, 10, 0, 1200640, 0, -10};
  write_dem(pkg("dem.tif"), 64, 64, gt, "EPSG:2056", GDT_Float32,
            [](int x, int y) { return 500.0 + x + y; });
  auto r = run(tiler() + " terrain " + pkg("dem.tif") + " --tiling local -o " + pkg("t.mbtiles"),
               dir_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<globe::XY> line{{2600050, 1200600}, {2600300, 1200300}, {2600610, 1200020}};
  write_text(pkg("l.geojson"),
             "{\"type\":\"FeatureCollection\",\"crs\":{\"type\":\"name\",\"properties\":"
             "{\"name\":\"urn:ogc:def:crs:EPSG::2056\"}},\"features\":[" +
                 feature(1, "a", "{\"type\":\"LineString\",\"coordinates\":" + coords(line) + "}") +
                 "]}");
  r = vectorize("lines " + pkg("l.geojson") + " --like " + pkg("t.mbtiles") + " --max-zoom 3 -o " +
                pkg("l.mbtiles"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  tileformat::PackageReader terrain(pkg("t.mbtiles")), lines(pkg("l.mbtiles"));
  for (const char* key :
       {"globe:scheme", "globe:crs", "globe:origin", "globe:root_size", "globe:roots"})
    EXPECT_EQ(terrain.meta(key), lines.meta(key)) << key;
  ASSERT_EQ(vectorize("extract " + pkg("l.mbtiles") + " --zoom 3 -o " + pkg("l3.gpkg")).exit_code,
            0);
  const auto back = read_lines(pkg("l3.gpkg"), "lines", "feature_id");
  ASSERT_TRUE(back.count(1));
  const double tile = std::stod(*terrain.meta("globe:root_size")) / 8;
  EXPECT_LE(directed_hausdorff(back.at(1), {line}), 0.25 * tile / 256 + tile / 4096 + 1e-6);
  EXPECT_LE(directed_hausdorff({line}, back.at(1)), 0.25 * tile / 256 + tile / 4096 + 1e-6);
  // --like and --tiling together are refused.
  r = vectorize("lines " + pkg("l.geojson") + " --like " + pkg("t.mbtiles") +
                " --tiling geodetic -o " + pkg("x.mbtiles"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
}

TEST_F(LinesCli, TerrainAndLinesOfOneAreaShareTheirDefaultView) {
  // One rule for `center` in every package kind: the deepest zoom whose one
  // tile holds the data (10 x 4 degrees fits a 11.25-degree geodetic tile,
  // zoom 4), at the middle of the bounds.
  const double gt[6] = {10, 0.1, 0, 44, 0, -0.1};
  write_dem(pkg("dem.tif"), 100, 40, gt, "EPSG:4326", GDT_Float32,
            [](int x, int y) { return 100.0 + x - y; });
  auto r = run(tiler() + " terrain " + pkg("dem.tif") + " --tiling geodetic --max-zoom 6 -o " +
                   pkg("t.mbtiles"),
               dir_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<globe::XY> line{{10, 40}, {15, 43}, {20, 44}};
  write_text(pkg("l.geojson"),
             "{\"type\":\"FeatureCollection\",\"features\":[" +
                 feature(1, "a", "{\"type\":\"LineString\",\"coordinates\":" + coords(line) + "}") +
                 "]}");
  r = vectorize("lines " + pkg("l.geojson") + " --tiling geodetic --max-zoom 8 -o " +
                pkg("l.mbtiles"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  tileformat::PackageReader terrain(pkg("t.mbtiles")), lines(pkg("l.mbtiles"));
  ASSERT_TRUE(terrain.meta("center") && lines.meta("center"));
  auto zoom_of = [](const std::string& center) {
    return std::stoi(center.substr(center.rfind(',') + 1));
  };
  EXPECT_EQ(zoom_of(*terrain.meta("center")), 4) << *terrain.meta("center");
  EXPECT_EQ(zoom_of(*lines.meta("center")), 4) << *lines.meta("center");
  EXPECT_EQ(lines.meta("center")->substr(0, 3), "15,") << *lines.meta("center");
}

struct BadCase {
  std::string name, args;
  int exit_code;
  std::string message;
};

TEST_F(LinesCli, BadInputGetsAClearErrorAndLeavesNothing) {
  // A shapefile (with .prj) made from the GeoJSON, then damaged copies.
  ASSERT_EQ(run("ogr2ogr -f 'ESRI Shapefile' " + pkg("s.shp") + " " + input_ +
                    " -nlt LINESTRING -where \"fid <= 3\"",
                dir_.path())
                .exit_code,
            0);
  for (std::string stem : {"noshx", "nodbf", "noprj"})
    for (std::string ext : {".shp", ".shx", ".dbf", ".prj"})
      fs::copy_file(pkg("s" + ext), pkg(stem + ext));
  fs::remove(pkg("noshx.shx"));
  fs::remove(pkg("nodbf.dbf"));
  fs::remove(pkg("noprj.prj"));
  write_text(pkg("empty.geojson"), "{\"type\":\"FeatureCollection\",\"features\":[]}");
  write_text(pkg("text.txt"), "this is not vector data\n");
  const std::vector<BadCase> cases = {
      {"missing", pkg("nothere.shp"), 1, "no such file"},
      {"no .shx", pkg("noshx.shp"), 1, ".shx) is missing"},
      {"no .dbf", pkg("nodbf.shp"), 1, ".dbf) is missing"},
      {"no .prj", pkg("noprj.shp"), 1, "pass --s_srs"},
      {"empty layer", pkg("empty.geojson"), 1, "no feature with usable"},
      {"not vector", pkg("text.txt"), 1, "not vector data"},
      {"unknown layer", input_ + " --layer roads", 2, "no such layer"},
      {"unknown where field", input_ + " --where \"speed > 3\"", 2, "--where"},
      {"unknown class field", input_ + " --class-field colour", 2, "no such field"},
      {"bad tiling", input_ + " --tiling mars", 2, "--tiling"},
      {"bad bbox", input_ + " --bbox 8,47,7,48", 2, "--bbox"},
      {"bad zoom range", input_ + " --min-zoom 9 --max-zoom 3", 2, "--min-zoom"},
      {"style of no class", input_ + " --style nosuchclass:color=#ff0000", 2,
       "no feature has class 'nosuchclass'"},
  };
  for (const BadCase& c : cases) {
    auto r = vectorize("lines " + c.args + " -o " + pkg("out.mbtiles"));
    EXPECT_EQ(r.exit_code, c.exit_code) << c.name << ": " << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.name << ": " << r.err;
    EXPECT_FALSE(fs::exists(pkg("out.mbtiles"))) << c.name;
    EXPECT_FALSE(fs::exists(pkg("out.mbtiles.tmp"))) << c.name;
  }
  // With --s_srs the shapefile without .prj works.
  EXPECT_EQ(vectorize("lines " + pkg("noprj.shp") + " --s_srs EPSG:4326 -o " + pkg("ok.mbtiles"))
                .exit_code,
            0);
  // An existing output is not replaced without --force.
  auto r = vectorize("lines " + input_ + " -o " + pkg("ok.mbtiles"));
  EXPECT_EQ(r.exit_code, 3) << r.err;
  // Inspection commands refuse other package kinds and missing files.
  r = vectorize("info " + pkg("nothere.mbtiles"));
  EXPECT_EQ(r.exit_code, 1);
  r = vectorize("extract " + pkg("ok.mbtiles") + " --zoom 30 -o " + pkg("x.gpkg"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_FALSE(fs::exists(pkg("x.gpkg")));
}

TEST_F(LinesCli, ValidateFindsADamagedTile) {
  ASSERT_EQ(vectorize("lines " + input_ + " -o " + pkg("a.mbtiles") + " --max-zoom 8").exit_code,
            0);
  {
    tileformat::SqliteDb db(pkg("a.mbtiles"), tileformat::SqliteDb::Mode::kReadWriteCreate);
    db.exec(
        "UPDATE blobs SET tile_data = substr(tile_data, 1, length(tile_data) - 3) "
        "WHERE blob_id = (SELECT min(blob_id) FROM blobs)");
  }
  auto r = vectorize("validate " + pkg("a.mbtiles"));
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.out.find("tileformat §4"), std::string::npos) << r.out;
}

}  // namespace
