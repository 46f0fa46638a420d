// `info --json` of every package kind: one JSON object whose shared part
// (kind, metadata, per-zoom tiles and bytes, totals) equals what the sqlite3
// program reads from the file itself, and whose kind section is there.
#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <string>
#include <utility>

#include "line_fixtures.hpp"
#include "point_fixtures.hpp"
#include "test_support.hpp"
#include "tileformat/json.hpp"

namespace {

using namespace globe_test;
using tileformat::JsonValue;

// Where the commands' output is captured.
const fs::path& scratch() {
  static TempDir dir("-out");
  return dir.path();
}

// One number from the sqlite3 program.
uint64_t sql_count(const std::string& package, const std::string& query) {
  const RunResult r = run("sqlite3 " + package + " \"" + query + "\"", scratch());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return std::stoull(r.out);
}

// The metadata table, name -> value, through sqlite3 (one row per line;
// values here hold no newline but may hold '|', hence the separator).
std::map<std::string, std::string> sql_metadata(const std::string& package) {
  const RunResult r = run(
      "sqlite3 -separator '\x1f' " + package + " \"SELECT name, value FROM metadata\"", scratch());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::map<std::string, std::string> m;
  size_t at = 0;
  while (at < r.out.size()) {
    const size_t end = r.out.find('\n', at);
    const std::string line = r.out.substr(at, end - at);
    const size_t sep = line.find('\x1f');
    if (sep != std::string::npos) m[line.substr(0, sep)] = line.substr(sep + 1);
    at = end == std::string::npos ? r.out.size() : end + 1;
  }
  return m;
}

void expect_shared_part(const JsonValue& info, const std::string& package, const std::string& kind,
                        const std::string& section) {
  EXPECT_EQ(info.find("package")->string(), package);
  EXPECT_EQ(info.find("kind")->string(), kind);
  EXPECT_EQ(uint64_t(info.find("file_bytes")->number()), fs::file_size(package));
  const std::map<std::string, std::string> meta = sql_metadata(package);
  ASSERT_EQ(info.find("metadata")->members().size(), meta.size());
  for (const auto& [k, v] : info.find("metadata")->members())
    EXPECT_EQ(v.string(), meta.at(k)) << k;
  EXPECT_EQ(uint64_t(info.find("tiles")->number()),
            sql_count(package, "SELECT count(*) FROM tiles"));
  uint64_t zoom_tiles = 0;
  for (const JsonValue& z : info.find("zooms")->array()) {
    const int zoom = int(z.find("zoom")->number());
    const std::string where = " FROM tiles WHERE zoom_level = " + std::to_string(zoom);
    EXPECT_EQ(uint64_t(z.find("tiles")->number()), sql_count(package, "SELECT count(*)" + where));
    EXPECT_EQ(uint64_t(z.find("bytes")->number()),
              sql_count(package, "SELECT sum(length(tile_data))" + where))
        << zoom;
    zoom_tiles += uint64_t(z.find("tiles")->number());
  }
  EXPECT_EQ(zoom_tiles, uint64_t(info.find("tiles")->number()));
  ASSERT_NE(info.find(section), nullptr) << section;
  EXPECT_TRUE(info.find(section)->is_object());
}

JsonValue info_json(const std::string& tool, const std::string& package) {
  const RunResult r = run(tool + " info --json " + package, scratch());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << "one line: " << r.out;
  return JsonValue::parse(r.out);
}

TEST(InfoCli, JsonOfEveryKindIsWhatThePackageHolds) {
  TempDir dir;
  const std::string terrain = (dir / "t.mbtiles").string(), analysis = (dir / "a.mbtiles").string(),
                    image = (dir / "i.mbtiles").string(), lines = (dir / "l.mbtiles").string(),
                    points = (dir / "p.mbtiles").string();
  write_text((dir / "l.geojson").string(),
             R"({"type":"FeatureCollection","features":[
{"type":"Feature","properties":{},"geometry":{"type":"LineString","coordinates":[[7,46],[8,47],[9,46.5]]}},
{"type":"Feature","properties":{},"geometry":{"type":"LineString","coordinates":[[7.5,46.2],[7.6,46.9]]}}]})");
  write_places_csv((dir / "p.csv").string(), {"a", "b"},
                   {{"x", 7.1, 46.1, {1, 2}}, {"y", 7.2, 46.3, {3, 4}}, {"z", 8.5, 46.9, {5, 6}}});
  ASSERT_TRUE(
      run_all({tiler() + " terrain -q " + sample("jacksboro.tif").string() + " -o " + terrain,
               tiler() + " analyze -q " + terrain + " --layers slope -o " + analysis,
               "gdal_translate -q -outsize 300 300 -ot Byte -scale " +
                   sample("jacksboro.tif").string() + " " + (dir / "i.tif").string(),
               tiler() + " imagery -q " + (dir / "i.tif").string() + " -o " + image,
               vectorize() + " lines -q " + (dir / "l.geojson").string() + " -o " + lines,
               vectorize() + " points -q " + (dir / "p.csv").string() +
                   " --xy lon,lat --fields a,b -o " + points},
              dir.path()));
  const JsonValue t = info_json(tiler(), terrain);
  expect_shared_part(t, terrain, "terrain", "terrain");
  EXPECT_EQ(t.find("terrain")->find("block_size")->number(), 257);
  const JsonValue a = info_json(tiler(), analysis);
  expect_shared_part(a, analysis, "analysis", "analysis");
  EXPECT_EQ(a.find("analysis")->find("layers")->array().at(0).find("name")->string(), "slope");
  const JsonValue i = info_json(tiler(), image);
  expect_shared_part(i, image, "image", "image");
  EXPECT_EQ(i.find("image")->find("stored")->find("png")->number() +
                i.find("image")->find("stored")->find("jpg")->number(),
            i.find("tiles")->number());
  const JsonValue l = info_json(vectorize(), lines);
  expect_shared_part(l, lines, "lines", "lines");
  EXPECT_EQ(l.find("lines")->find("features")->number(), 2);
  const JsonValue p = info_json(vectorize(), points);
  expect_shared_part(p, points, "points", "points");
  EXPECT_EQ(p.find("points")->find("places")->number(), 3);

  // Each tool reads its own kinds; given another's, every verb names the
  // file, the kind and the tool that reads it, and writes nothing.
  const std::pair<std::string, std::string> wrong[] = {{vectorize(), terrain},
                                                       {vectorize(), image},
                                                       {vectorize(), analysis},
                                                       {tiler(), lines},
                                                       {tiler(), points}};
  const char* kind_of[] = {"a terrain", "an image", "an analysis", "a line-cluster", "a point"};
  for (size_t k = 0; k < std::size(wrong); ++k) {
    const auto& [tool, package] = wrong[k];
    const bool tiler_reads = tool == vectorize();
    const std::string reader = tiler_reads ? "globe-tiler" : "globe-vectorize";
    const std::string self = tiler_reads ? "globe-vectorize" : "globe-tiler";
    const std::string out = (dir / "wrong.out").string();
    for (const std::string verb : {"info", "validate", "extract"}) {
      const RunResult r = run(tool + " " + verb + " " + package +
                                  (verb == "extract" ? " --zoom 0 -o " + out : std::string()),
                              dir.path());
      EXPECT_EQ(r.exit_code, 1) << verb << " " << package << ": " << r.err;
      EXPECT_NE(r.err.find(package + ": " + kind_of[k] + " package, which " + self + " " + verb +
                           " does not read; run " + reader + " " + verb + " " + package),
                std::string::npos)
          << r.err;
      EXPECT_FALSE(fs::exists(out));
    }
  }
}

}  // namespace
