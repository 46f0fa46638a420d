// globe-view with bundled flows (docs/bundles.md "Viewer") as a user runs
// them: the US flights bundled over the FlightGear airways, drawn over the
// etopo20 globe against an expected PNG; picking a bundle highlights every
// connection through it (checked against the package's features table read
// by the sqlite3 program); picking a plain line names its feature; the
// window names the bundle a click picked; --bundles 3d against an expected
// PNG, and lifted lines clear a ridge they cross.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "raster_fixtures.hpp"
#include "render_fixtures.hpp"
#include "test_paths.hpp"
#include "test_support.hpp"
#include "tileformat/json.hpp"

namespace {

using namespace globe_test;

struct Packages {
  fs::path dir;
  std::string world, bundles, airways;
};

const Packages& packages() {
  static const Packages p = [] {
    Packages k;
    k.dir = shared_folder("globe-view-bundles", [](const fs::path& dir) {
      auto at = [&](const char* name) { return (dir / name).string(); };
      return run_all({tiler() + " terrain -q " + sample("etopo20.tif").string() +
                          " --max-zoom 4 -o " + at("world.mbtiles"),
                      vectorize() + " bundle -q " + sample("us_flights_airport.csv").string() +
                          " --from-id origin --to-id destination --weight count --locations " +
                          sample("us_airports.csv").string() + " --id-field iata --network " +
                          sample("airways.geojson").string() + " -o " + at("flights.mbtiles"),
                      vectorize() + " lines -q " + sample("airways.geojson").string() +
                          " --max-zoom 6 -o " + at("airways.mbtiles")},
                     dir);
    });
    k.world = (k.dir / "world.mbtiles").string();
    k.bundles = (k.dir / "flights.mbtiles").string();
    k.airways = (k.dir / "airways.mbtiles").string();
    return k;
  }();
  return p;
}

const std::string kView = " --size 480x300 --camera=-97,39,5000000,0,0";

std::pair<double, double> lonlat_pair(const tileformat::JsonValue& a) {
  return {a.array()[0].number(), a.array()[1].number()};
}

// The highlight colour (line_layer.cpp), which no default style uses.
bool is_highlight(const uint8_t* p) {
  return p[0] < 60 && p[1] > 190 && p[2] > 210;
}

struct Highlight {
  size_t pixels = 0;
  int min_x = 1 << 30, max_x = -1;
  bool near(const std::vector<uint8_t>& rgb, int w, int x, int y) const {
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx)
        if (is_highlight(&rgb[(size_t(y + dy) * w + x + dx) * 3])) return true;
    return false;
  }
};

Highlight highlight_of(const std::vector<uint8_t>& rgb, int w) {
  Highlight h;
  for (size_t i = 0; i + 2 < rgb.size(); i += 3)
    if (is_highlight(&rgb[i])) {
      ++h.pixels;
      const int x = int(i / 3 % w);
      h.min_x = std::min(h.min_x, x), h.max_x = std::max(h.max_x, x);
    }
  return h;
}

// Runs a headless pick; returns its line on stdout (without the newline).
std::string pick(const std::string& packages, int x, int y, const std::string& png,
                 const fs::path& dir) {
  const RunResult r = run(viewer() + " " + packages + kView + " --pick " + std::to_string(x) + "," +
                              std::to_string(y) + " --snapshot " + png,
                          dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::string line = r.out;
  while (!line.empty() && line.back() == '\n')
    line.pop_back();
  return line;
}

}  // namespace

TEST(ViewerBundles, BundledFlightsOverTheGlobeMatchExpected) {
  const Packages& k = packages();
  TempDir dir;
  const std::string out = (dir / "bundles.png").string();
  const RunResult r =
      run(viewer() + " " + k.world + " " + k.bundles + kView + " --snapshot " + out, dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_image(out, "us_flights_bundled");
  int w = 0, h = 0;
  EXPECT_EQ(highlight_of(read_rgb(out, w, h), w).pixels, 0u) << "highlight without a pick";
}

// The bundle under a pixel of a transcontinental corridor: the count and
// weight printed are those of the connections whose paths list it (a scan of
// the features table here), and the snapshot highlights their whole paths,
// far beyond the picked bundle.
TEST(ViewerBundles, PickingABundleHighlightsTheConnectionsThroughIt) {
  const Packages& k = packages();
  TempDir dir;
  const std::string png = (dir / "pick.png").string();
  const std::string said = pick(k.world + " " + k.bundles, 300, 150, png, dir.path());
  unsigned long long bundle = 0, count = 0;
  double weight = 0;
  ASSERT_EQ(std::sscanf(said.c_str(), "bundle %llu: weight %lf, %llu connections", &bundle, &weight,
                        &count),
            3)
      << said;

  const RunResult rows = run(
      "sqlite3 " + k.bundles + " \"SELECT properties FROM features WHERE layer = 'connections'\"",
      dir.path());
  ASSERT_EQ(rows.exit_code, 0) << rows.err;
  std::istringstream in(rows.out);
  unsigned long long through = 0;
  double through_weight = 0;
  for (std::string line; std::getline(in, line);) {
    const auto props = tileformat::JsonValue::parse(line);
    const tileformat::JsonValue* path = props.find("bundles");
    if (!path) continue;
    for (const tileformat::JsonValue& b : path->array())
      if (static_cast<unsigned long long>(b.number()) == bundle) {
        ++through;
        through_weight += props.find("weight")->number();
      }
  }
  EXPECT_EQ(count, through);
  EXPECT_NEAR(weight, through_weight, 1e-5 * through_weight);
  EXPECT_GT(count, 10u) << "pick a busier corridor";

  int w = 0, h = 0;
  const auto rgb = read_rgb(png, w, h);
  const Highlight lit = highlight_of(rgb, w);
  EXPECT_TRUE(lit.near(rgb, w, 300, 150)) << "the picked bundle is not highlighted";
  EXPECT_GT(lit.max_x - lit.min_x, 200)
      << "the connections' paths are not highlighted coast to coast";
  EXPECT_LT(lit.pixels, rgb.size() / 3 / 10) << "far more than the connections is highlighted";
}

TEST(ViewerBundles, PickingNothingHighlightsNothing) {
  const Packages& k = packages();
  TempDir dir;
  const std::string png = (dir / "sky.png").string();
  EXPECT_EQ(pick(k.world + " " + k.bundles, 3, 3, png, dir.path()), "");
  int w = 0, h = 0;
  EXPECT_EQ(highlight_of(read_rgb(png, w, h), w).pixels, 0u);
}

// A plain line package: the feature drawn at the pixel, with its layer and
// attributes, highlighted alone.
TEST(ViewerBundles, PickingAPlainLineNamesItsFeature) {
  const Packages& k = packages();
  TempDir dir;
  // A pixel on a line: the first drawn pixel (not terrain grey) of the row.
  const std::string plain = (dir / "plain.png").string();
  ASSERT_EQ(
      run(viewer() + " " + k.world + " " + k.airways + kView + " --snapshot " + plain, dir.path())
          .exit_code,
      0);
  int w = 0, h = 0;
  const auto rgb = read_rgb(plain, w, h);
  int x = -1;
  const int y = h / 2;
  for (int i = w / 4; i < 3 * w / 4 && x < 0; ++i) {
    const uint8_t* p = &rgb[(size_t(y) * w + i) * 3];
    const uint8_t* q = &rgb[(size_t(y) * w + i + 1) * 3];
    if (std::abs(int(p[0]) - int(p[2])) > 60 && std::abs(int(q[0]) - int(q[2])) > 60) x = i;
  }
  ASSERT_GE(x, 0) << "no airway across the middle row";
  const std::string png = (dir / "pick.png").string();
  const std::string said = pick(k.world + " " + k.airways, x, y, png, dir.path());
  EXPECT_EQ(said.rfind("feature ", 0), 0u) << said;
  EXPECT_NE(said.find("(airways): {"), std::string::npos) << said;
  const auto lit_rgb = read_rgb(png, w, h);
  const Highlight lit = highlight_of(lit_rgb, w);
  EXPECT_TRUE(lit.near(lit_rgb, w, x, y));
  EXPECT_LT(lit.pixels, size_t(w) * h / 20) << "one airway, not the network";
}

// The window under a virtual X server: a click on the corridor names the
// bundle in the title.
TEST(ViewerBundlesWindow, AClickNamesTheBundleInTheTitle) {
  const Packages& k = packages();
  TempDir dir;
  const RunResult w =
      run("xvfb-run -a -s '-screen 0 640x480x24' " + globe_test::paths::test_data_dir() +
              "/window/hover_title.sh --click " + dir.path().string() + " 300 150 " + viewer() +
              " --platform glfw" + kView + " " + k.world + " " + k.bundles,
          dir.path());
  ASSERT_EQ(w.exit_code, 0) << w.err << read_file(dir / "viewer.stderr");
  EXPECT_NE(w.out.find("globe-view  bundle "), std::string::npos) << w.out;
  EXPECT_NE(w.out.find(" connections"), std::string::npos) << w.out;
}

// Readability at continental scale (docs/bundles.md "Weights and styles"):
// the US flights at 1280 x 720 over North America cover at most 20 % of the
// land pixels (land: a render of the heights with a two-colour ramp), and
// the 20 heaviest bundles are drawn on top: a pick at each one's midpoint
// (on its zoom-3 curve, from `extract`) names it, or a heavier bundle that
// covers it there, and most name themselves.
TEST(ViewerBundles, AContinentalViewShowsTheHeaviestCorridorsWithLittleInk) {
  const Packages& k = packages();
  TempDir dir;
  const std::string view = " --size 1280x720 --camera=-97,39,5000000,0,0";
  std::ofstream(dir / "land.txt") << "-12000 0 0 0\n-0.01 0 0 0\n0 255 255 255\n9000 255 255 255\n";
  const std::string base = (dir / "base.png").string(), land = (dir / "land.png").string(),
                    flows = (dir / "flows.png").string();
  ASSERT_EQ(run(viewer() + " " + k.world + view + " --snapshot " + base, dir.path()).exit_code, 0);
  ASSERT_EQ(run(viewer() + " " + k.world + view + " --shading elevation --colormap " +
                    (dir / "land.txt").string() + " --snapshot " + land,
                dir.path())
                .exit_code,
            0);

  // Bundle weights, heaviest first.
  const RunResult rows = run("sqlite3 -separator ' ' " + k.bundles +
                                 " \"SELECT id, json_extract(properties, '$.weight') FROM features "
                                 "WHERE layer = 'bundles' ORDER BY 2 DESC, 1\"",
                             dir.path());
  ASSERT_EQ(rows.exit_code, 0) << rows.err;
  std::map<uint64_t, double> weight;
  std::vector<uint64_t> heaviest;
  std::istringstream in(rows.out);
  for (uint64_t id; in >> id;) {
    in >> weight[id];
    if (heaviest.size() < 20) heaviest.push_back(id);
  }
  ASSERT_EQ(heaviest.size(), 20u);

  // Midpoints: on each bundle's zoom-3 curve, the point as far (on the
  // sphere) from its two ends, searched along every segment.
  const std::string curves = (dir / "z3.geojson").string();
  ASSERT_EQ(run(vectorize() + " extract -q " + k.bundles + " --zoom 3 -o " + curves, dir.path())
                .exit_code,
            0);
  const auto doc = tileformat::JsonValue::parse(read_file(curves));
  auto lonlat = [](const tileformat::JsonValue& c) {  // EPSG:3857 -> degrees
    const double r = 6378137.0;
    return std::pair(c.array()[0].number() / r * 180 / M_PI,
                     (2 * std::atan(std::exp(c.array()[1].number() / r)) - M_PI / 2) * 180 / M_PI);
  };
  std::map<uint64_t, std::pair<double, std::pair<double, double>>> mid;  // id -> (score, lon/lat)
  for (const auto& f : doc.find("features")->array()) {
    const auto& props = *f.find("properties");
    const uint64_t id = static_cast<uint64_t>(props.find("feature_id")->number());
    if (std::find(heaviest.begin(), heaviest.end(), id) == heaviest.end()) continue;
    const auto& p = *props.find("properties");
    const auto from = lonlat_pair(*p.find("from")), to = lonlat_pair(*p.find("to"));
    const auto& coords = f.find("geometry")->find("coordinates")->array();
    for (size_t i = 0; i + 1 < coords.size(); ++i) {
      const auto a = lonlat(coords[i]), b = lonlat(coords[i + 1]);
      for (int s = 0; s <= 32; ++s) {
        const std::pair<double, double> q{a.first + (b.first - a.first) * s / 32,
                                          a.second + (b.second - a.second) * s / 32};
        const double score = std::fabs(haversine_m(q.first, q.second, from.first, from.second) -
                                       haversine_m(q.first, q.second, to.first, to.second));
        auto it = mid.find(id);
        if (it == mid.end() || score < it->second.first) mid[id] = {score, q};
      }
    }
  }
  std::string picks;
  for (uint64_t id : heaviest) {
    ASSERT_TRUE(mid.count(id)) << "bundle " << id << " is not drawn at zoom 3";
    char at[64];
    std::snprintf(at, sizeof at, " --pick @%.6f,%.6f", mid[id].second.first, mid[id].second.second);
    picks += at;
  }
  // The last pick, at the sky's corner, clears the highlight for the snapshot.
  const RunResult picked = run(
      viewer() + " " + k.world + " " + k.bundles + view + picks + " --pick 0,0 --snapshot " + flows,
      dir.path());
  ASSERT_EQ(picked.exit_code, 0) << picked.err;
  std::istringstream said(picked.out);
  int themselves = 0;
  for (uint64_t id : heaviest) {
    std::string line;
    std::getline(said, line);
    unsigned long long found = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "bundle %llu:", &found), 1)
        << "bundle " << id << " (weight " << weight[id] << ") not found at its midpoint: '" << line
        << "'";
    EXPECT_GE(weight[found], weight[id])
        << "bundle " << id << " is under the lighter bundle " << found;
    themselves += found == id;
  }
  EXPECT_GE(themselves, 15) << "of the 20 heaviest bundles, picked at their midpoints";

  // Ink: pixels the flows change, on land, outside the legend's corner.
  int w = 0, h = 0;
  const auto plain = read_rgb(base, w, h), mask = read_rgb(land, w, h),
             drawn = read_rgb(flows, w, h);
  size_t land_px = 0, ink = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = (size_t(y) * w + x) * 3;
      if (mask[i] < 200 || mask[i + 1] < 200 || mask[i + 2] < 200) continue;
      if (x < 260 && y > h - 170) continue;  // the legend
      ++land_px;
      for (int c = 0; c < 3; ++c)
        if (std::abs(int(drawn[i + c]) - int(plain[i + c])) > 8) {
          ++ink;
          break;
        }
    }
  ASSERT_GT(land_px, size_t(w) * h / 4);
  const double share = double(ink) / double(land_px);
  EXPECT_LE(share, 0.20) << ink << " of " << land_px << " land pixels carry flows";
  std::printf(
      "ink: %.1f %% of %zu land pixels; %d of the 20 heaviest bundles picked at their "
      "midpoints\n",
      100 * share, land_px, themselves);
}

TEST(ViewerBundles, BundlesIn3dOverTheGlobeMatchExpected) {
  const Packages& k = packages();
  TempDir dir;
  const std::string out = (dir / "bundles3d.png").string();
  const RunResult r = run(viewer() + " " + k.world + " " + k.bundles +
                              " --bundles 3d --exaggeration 20 --size 480x300 "
                              "--camera=-97,25,1500000,0,40 --snapshot " +
                              out,
                          dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_image(out, "us_flights_bundled_3d");
}

// A straight 2-vertex line across a narrow 3,000 m ridge on a plain, seen
// from above a little obliquely: lifted 1,000 m, the line climbs over the
// crest (as high on screen as the line draped on it) and no column along it
// is hidden by the ridge, as it would be for a chord lifted 1,000 m from its
// two ends, which passes through the ridge. (A lift of 100 m is not enough
// here: the heights are sampled at points and rings around them, and this
// ridge is narrower than the ring; docs/bundles.md "Viewer".)
TEST(ViewerBundles, LiftedLinesClearARidgeTheyCross) {
  TempDir dir;
  const std::string dem = (dir / "ridge.tif").string();
  const int n = 512;
  const double gt[6] = {10, 1.0 / n, 0, 47, 0, -1.0 / n};
  write_dem(dem, n, n, gt, "EPSG:4326", GDT_Float32, [&](int x, int) {
    const double d = (x - n / 2) / 3.0;
    return 3000 * std::exp(-d * d);
  });
  std::ofstream(dir / "line.geojson")
      << R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},)"
      << R"("geometry":{"type":"LineString","coordinates":[[10.1,46.5],[10.9,46.5]]}}]})";
  const std::string terrain = (dir / "ridge.mbtiles").string(),
                    line = (dir / "line.mbtiles").string();
  ASSERT_EQ(run(tiler() + " terrain -q " + dem + " -o " + terrain, dir.path()).exit_code, 0);
  const RunResult lines = run(vectorize() + " lines -q " + (dir / "line.geojson").string() +
                                  " -o " + line + " --style 'line:color=#ff0000,width=3px'",
                              dir.path());
  ASSERT_EQ(lines.exit_code, 0) << lines.err;
  struct Trace {
    int first = -1, last = -1, top = 1 << 30;
    std::vector<bool> column;
  };
  auto trace = [&](const std::string& mode) {
    const std::string png = (dir / (mode + ".png")).string();
    const RunResult r = run(viewer() + " " + terrain + " " + line + " --lines " + mode +
                                " --lift 1000 --size 320x180 --camera=10.45,46.42,15000,0,25 "
                                "--snapshot " +
                                png,
                            dir.path());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    int w = 0, h = 0;
    const auto rgb = read_rgb(png, w, h);
    Trace t;
    t.column.assign(size_t(w), false);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const uint8_t* p = &rgb[(size_t(y) * w + x) * 3];
        if (p[0] > 200 && p[1] < 60 && p[2] < 60) {
          t.column[size_t(x)] = true;
          t.top = std::min(t.top, y);
          if (t.first < 0 || x < t.first) t.first = x;
          t.last = std::max(t.last, x);
        }
      }
    return t;
  };
  const Trace draped = trace("deferred"), lifted = trace("lifted");
  ASSERT_GE(lifted.first, 0) << "no lifted line drawn";
  ASSERT_GE(draped.first, 0);
  for (int x = lifted.first; x <= lifted.last; ++x)
    EXPECT_TRUE(lifted.column[size_t(x)]) << "the ridge hides the lifted line at column " << x;
  EXPECT_LE(lifted.top, draped.top + 1) << "the lifted line does not climb over the crest";
}
