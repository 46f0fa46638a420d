// Lines drawn per pixel beyond a plain fill:
//  - procedural patterns (docs/viewer.md "Line patterns"): railway ties,
//    arrows, zigzag and dots from the distance along and across the line.
//    The four on parallel lines over a flat base match an expected picture;
//    the arrows point along the line's vertex order, checked from the drawn
//    chevrons' shape (the arms trail the apex) on a line drawn west to east
//    and the same line drawn east to west;
//  - colour by the ground under the line (docs/viewer.md "Lines coloured by
//    the ground"): gdal_contour's 50 m contours coloured by height read back
//    their own level from their colours; coloured by slope they match an
//    expected picture (the street-slope map of the thesis's Figure 4.18).
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "render_fixtures.hpp"
#include "test_support.hpp"

namespace {

using namespace globe_test;

// A GeoJSON file of LineStrings (lon/lat pairs) with a "kind" property each.
void write_lines(const fs::path& path,
                 const std::vector<std::pair<std::string, std::vector<double>>>& lines) {
  std::ofstream f(path);
  f << R"({"type":"FeatureCollection","features":[)";
  for (size_t i = 0; i < lines.size(); ++i) {
    f << (i ? "," : "") << R"({"type":"Feature","properties":{"kind":")" << lines[i].first
      << R"("},"geometry":{"type":"LineString","coordinates":[)";
    const std::vector<double>& c = lines[i].second;
    for (size_t k = 0; k + 1 < c.size(); k += 2)
      f << (k ? "," : "") << "[" << c[k] << "," << c[k + 1] << "]";
    f << "]}}";
  }
  f << "]}\n";
}

RunResult view(const std::string& args, const fs::path& dir) {
  return run(viewer() + " --platform osmesa " + args, dir);
}

TEST(ViewerLinePatterns, FourPatternsMatchExpected) {
  TempDir dir;
  std::vector<std::pair<std::string, std::vector<double>>> lines;
  const char* kinds[] = {"rail", "arrow", "zig", "dot"};
  for (int i = 0; i < 4; ++i)  // west to east, a bend in the middle
    lines.push_back(
        {kinds[i], {10.0, 45.0 + 0.01 * i, 10.05, 45.004 + 0.01 * i, 10.1, 45.0 + 0.01 * i}});
  write_lines(dir / "p.geojson", lines);
  const std::string pkg = (dir / "p.mbtiles").string(), png = (dir / "p.png").string();
  ASSERT_TRUE(run_all(
      {vectorize() + " lines -q " + (dir / "p.geojson").string() + " --class-field kind -o " + pkg +
       " --style 'rail:pattern=railway,width=7px,color=#333333'"
       " --style 'arrow:pattern=arrows,width=10px,color=#1f4e9c'"
       " --style 'zig:pattern=zigzag@12px,width=8px,color=#b2182b'"
       " --style 'dot:pattern=dots,width=6px,color=#1b7837'"},
      dir.path()));
  const RunResult r = view(pkg + " --flat --fit --size 480x270 --snapshot " + png, dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_image(png, "line_patterns");
}

// The mean x of the chevron pixels at the edges of the line's width minus
// that of the pixels nearer its centre, over the middle third of the frame:
// negative where the arms trail to the west (arrows pointing east).
double arm_offset(const std::string& png) {
  int w = 0, h = 0;
  const std::vector<uint8_t> rgb = read_rgb(png, w, h);
  auto blue = [&](int x, int y) {
    const uint8_t* p = &rgb[3 * (size_t(y) * w + x)];
    return p[2] > p[0] + 60;
  };
  // The line's rows: its centre and half width.
  int top = h, bottom = -1;
  for (int y = 0; y < h; ++y)
    for (int x = w / 3; x < 2 * w / 3; ++x)
      if (blue(x, y)) top = std::min(top, y), bottom = std::max(bottom, y);
  EXPECT_GT(bottom - top, 10) << "no wide blue line drawn";
  const double centre = 0.5 * (top + bottom), hw = 0.5 * (bottom - top);
  double edge_x = 0, mid_x = 0;
  int edge_n = 0, mid_n = 0;
  for (int y = top; y <= bottom; ++y) {
    const double across = std::abs(y - centre) / hw;
    for (int x = w / 3; x < 2 * w / 3; ++x) {
      if (!blue(x, y)) continue;
      if (across > 0.65) edge_x += x, ++edge_n;
      if (across > 0.35 && across < 0.5) mid_x += x, ++mid_n;
    }
  }
  EXPECT_GT(edge_n, 10);
  EXPECT_GT(mid_n, 10);
  return edge_n && mid_n ? edge_x / edge_n - mid_x / mid_n : 0;
}

TEST(ViewerLinePatterns, ArrowsPointAlongTheVertexOrder) {
  TempDir dir;
  // 3 km along 45 N: one whole chevron every 1.5 km, widths in metres.
  const double west = 10.0, east = 10.0 + 3000 / (111320 * std::cos(45 * M_PI / 180));
  double offsets[2] = {0, 0};
  for (int reversed = 0; reversed < 2; ++reversed) {
    const std::string name = reversed ? "westward" : "eastward";
    const fs::path json = dir / (name + ".geojson");
    write_lines(json, {{"flow", reversed ? std::vector<double>{east, 45.0, west, 45.0}
                                         : std::vector<double>{west, 45.0, east, 45.0}}});
    const std::string pkg = (dir / (name + ".mbtiles")).string();
    const std::string png = (dir / (name + ".png")).string();
    ASSERT_TRUE(run_all({vectorize() + " lines -q " + json.string() + " --class-field kind -o " +
                         pkg + " --style 'flow:pattern=arrows@1500m,width=300m,color=#0000ff'"},
                        dir.path()));
    const RunResult r =
        view(pkg + " --flat --size 480x270 --camera=" + std::to_string((west + east) / 2) +
                 ",45,1500,0,0 --snapshot " + png,
             dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    offsets[reversed] = arm_offset(png);
  }
  std::printf("arm ends minus arm middles, x: eastward %.1f px, westward %.1f px\n", offsets[0],
              offsets[1]);
  EXPECT_LT(offsets[0], -2.0) << "eastward arrows: the arms trail to the west";
  EXPECT_GT(offsets[1], 2.0) << "westward arrows: the arms trail to the east";
}

TEST(ViewerLinePatterns, UnknownPatternsAreClearErrors) {
  TempDir dir;
  write_lines(dir / "l.geojson", {{"a", {10.0, 45.0, 10.1, 45.0}}});
  const RunResult r =
      run(vectorize() + " lines -q " + (dir / "l.geojson").string() + " --class-field kind -o " +
              (dir / "l.mbtiles").string() + " --style 'a:pattern=stripes'",
          dir.path());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("pattern 'stripes' is not railway, arrows, zigzag or dots"),
            std::string::npos)
      << r.err;
  std::ofstream(dir / "style.json") << R"({"a": {"pattern": "stripes"}})";
  ASSERT_TRUE(run_all({vectorize() + " lines -q " + (dir / "l.geojson").string() +
                       " --class-field kind -o " + (dir / "l.mbtiles").string()},
                      dir.path()));
  const RunResult v =
      view((dir / "l.mbtiles").string() + " --style " + (dir / "style.json").string() +
               " --snapshot " + (dir / "x.png").string(),
           dir.path());
  EXPECT_EQ(v.exit_code, 1) << v.err;
  EXPECT_NE(v.err.find("\"pattern\": expected \"\" or one of railway"), std::string::npos) << v.err;
}

// jacksboro with its 50 m contours (gdal_contour), shared by the tests below.
struct Contours {
  std::string terrain, lines;
};
const Contours& contours() {
  static const Contours c = [] {
    const fs::path dir = shared_folder("globe-view-line-colours", [](const fs::path& d) {
      const std::string j = sample("jacksboro.tif").string();
      return run_all({tiler() + " terrain -q " + j + " -o " + (d / "j.mbtiles").string(),
                      "gdal_contour -q -i 50 -a elev " + j + " " + (d / "c50.shp").string(),
                      vectorize() + " lines -q " + (d / "c50.shp").string() + " -o " +
                          (d / "c50.mbtiles").string()},
                     d);
    });
    return Contours{(dir / "j.mbtiles").string(), (dir / "c50.mbtiles").string()};
  }();
  return c;
}

constexpr const char* kContourCamera = " --camera=-84.30,36.55,2500,30,65 --size 480x270";

TEST(ViewerLineColours, ContoursColouredByHeightShowTheirOwnLevel) {
  TempDir dir;
  // Blue at 200 m to red at 1100 m, a colour file beside the style file.
  std::ofstream(dir / "ramp.txt") << "200 0 0 255\n1100 255 0 0\n";
  std::ofstream(dir / "style.json") << R"({"c50": {"color": "height:ramp.txt", "width": 3}})";
  const std::string png = (dir / "h.png").string();
  // Top-down, so a pixel's ground lies close to the line's level.
  const RunResult r = view(contours().terrain + " " + contours().lines + " --style " +
                               (dir / "style.json").string() +
                               " --camera=-84.25,36.50,3000,0,0 --size 480x270 --snapshot " + png,
                           dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int w = 0, h = 0;
  const std::vector<uint8_t> rgb = read_rgb(png, w, h);
  size_t lines = 0, on_level = 0;
  for (size_t i = 0; i + 2 < rgb.size(); i += 3) {
    const int R = rgb[i], G = rgb[i + 1], B = rgb[i + 2];
    if (G > 10 || R + B < 245) continue;  // only the lines' fully covered pixels
    ++lines;
    const double height = 200 + 900.0 * R / (R + B);
    on_level += std::abs(height - 50 * std::round(height / 50)) <= 12;
  }
  std::printf("height-coloured contours: %zu line pixels, %.1f %% within 12 m of a 50 m level\n",
              lines, 100.0 * on_level / std::max<size_t>(lines, 1));
  EXPECT_GT(lines, size_t(w) * h / 50);
  // Chance would put 48 % within 12 m of a level; a 3 px line on a 30 degree
  // slope spans +-8 m of ground around its level.
  EXPECT_GE(double(on_level) / double(lines), 0.95);
}

TEST(ViewerLineColours, ContoursColouredBySlopeMatchExpected) {
  TempDir dir;
  std::ofstream(dir / "style.json") << R"({"c50": {"color": "slope", "width": 2}})";
  const std::string png = (dir / "s.png").string();
  const RunResult r =
      view(contours().terrain + " " + contours().lines + " --style " +
               (dir / "style.json").string() + kContourCamera + " --snapshot " + png,
           dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_image(png, "line_colour_by_slope");
  // A missing colour file is named.
  std::ofstream(dir / "bad.json") << R"({"c50": {"color": "slope:nosuch.txt"}})";
  const RunResult bad = view(contours().terrain + " " + contours().lines + " --style " +
                                 (dir / "bad.json").string() + " --snapshot " + png,
                             dir.path());
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("nosuch.txt"), std::string::npos) << bad.err;
}

}  // namespace
