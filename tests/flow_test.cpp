// globe-tiler analyze --layers flow as a user runs it: streams against GRASS
// r.watershed -s (single flow direction) on the terrain's own finest zoom of
// two real DEMs; the out-of-core solve equal to the in-memory one; water
// conserved; upstream areas across the antimeridian and next to a pole
// against a brute force written here (cells counted upstream, their areas on
// the WGS84 ellipsoid); the whole world drained only at its polar rows;
// peak memory within --memory-mb.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "raster_fixtures.hpp"
#include "test_support.hpp"

namespace {

using namespace globe_test;

constexpr double kDeg = std::numbers::pi / 180;

// The area of the WGS84 ellipsoid between two latitudes (degrees) over
// `dlon` degrees of longitude (the authalic zone formula).
double ellipsoid_zone_area(double north, double south, double dlon) {
  const double a = 6378137.0, f = 1 / 298.257223563, b = a * (1 - f), e2 = f * (2 - f);
  const double e = std::sqrt(e2);
  auto zone = [&](double phi) {
    const double s = std::sin(std::clamp(phi, -90.0, 90.0) * kDeg);
    return b * b / 2 * (s / (1 - e2 * s * s) + std::log((1 + e * s) / (1 - e * s)) / (2 * e));
  };
  return dlon * kDeg * std::abs(zone(north) - zone(south));
}

// A geodetic cell centred at `lat`, `sp` degrees a side.
double ellipsoid_cell_area(double lat, double sp) {
  return ellipsoid_zone_area(lat + sp / 2, lat - sp / 2, sp);
}

// Runs GRASS's r.watershed -s on a GeoTIFF in a throwaway location; returns
// the accumulation raster (cells; negative where water may come from
// outside the map: compared by magnitude).
Raster grass_accumulation(const TempDir& dir, const std::string& dem) {
  const std::string out = (dir / "grass_acc.tif").string();
  const std::string script = "r.in.gdal -o --q input=" + dem +
                             " output=dem && g.region raster=dem && " +
                             "r.watershed -s --q elevation=dem accumulation=acc && " +
                             "r.out.gdal --q -c type=Float64 input=acc output=" + out;
  const RunResult r =
      run("grass --tmp-location " + dem + " --exec bash -c '" + script + "'", dir.path());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return read_raster(out);
}

struct GrassCase {
  const char* name;
  const char* file;
  const char* tiling;
  const char* method;  // --flow-method
  // GDAL commands making the DEM from the sample, {in}, {out} and {dir}
  // standing for the sample, the DEM and the test's folder ("" for the
  // sample itself).
  const char* prepare;
  double stream_cells;  // upstream cells of a stream cell
  // The largest basin's outlet: the same cell within one, its area within
  // this share (0: not checked, where the largest outlet lies on the sea
  // floor at the region's edge, an abyssal plain both route differently).
  double basin_tolerance;
  // Shares of stream cells matched within one cell: GRASS's by ours, ours
  // by GRASS's. Measured 98.9 % / 87.7 % (brasilia), 99.97 % / 99.5 %
  // (jacksboro); before depressions were routed like r.watershed's search
  // (depression_routing.hpp) 90.6 % / 79.9 % and 93.9 % / 94.0 %. Ours has
  // more stream cells away from GRASS's on brasilia: across its broad valley
  // floors, heights a few centimetres apart, some rivers run a few cells
  // beside GRASS's (docs/analysis.md, "Checked").
  double peer_share, our_share;
};

void PrintTo(const GrassCase& c, std::ostream* os) {
  *os << c.name;
}

class FlowVsGrass : public ::testing::TestWithParam<GrassCase> {};

// Stream cells: upstream area of at least 1,000 cells. GRASS's must have one
// of ours within one cell (and the other way round, so that marking
// everything a stream cannot pass); the largest basin's outlet must agree,
// and its area within 4 %.
TEST_P(FlowVsGrass, StreamsAndTheLargestOutletAgree) {
  TempDir dir;
  const std::string pkg = (dir / "t.mbtiles").string(), ana = (dir / "a.mbtiles").string();
  const std::string dem = (dir / "dem.tif").string(), acc = (dir / "acc.tif").string();
  std::string input = sample(GetParam().file).string();
  if (*GetParam().prepare) {
    std::string command = GetParam().prepare;
    const std::string made = (dir / "region.tif").string();
    for (const auto& [from, to] :
         {std::pair{std::string("{in}"), input}, std::pair{std::string("{out}"), made},
          std::pair{std::string("{dir}"), dir.path().string()}})
      for (size_t at = command.find(from); at != std::string::npos; at = command.find(from, at))
        command.replace(at, from.size(), to);
    const RunResult c = run(command, dir.path());
    ASSERT_EQ(c.exit_code, 0) << command << "\n" << c.err;
    input = made;
  }
  ASSERT_TRUE(build_terrain(std::string("--tiling ") + GetParam().tiling, input, pkg, dir.path()));
  const RunResult a = run(tiler() + " analyze -q --layers flow --flow-method " + GetParam().method +
                              " " + pkg + " -o " + ana,
                          dir.path());
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const RunResult info = run(tiler() + " info " + pkg, dir.path());
  const long long maxzoom = integer_after(info.out, "maxzoom");
  ASSERT_GE(maxzoom, 0) << info.out;
  const std::string z = std::to_string(maxzoom);
  ASSERT_EQ(run(tiler() + " extract " + pkg + " --zoom " + z + " -o " + dem, dir.path()).exit_code,
            0);
  const RunResult e =
      run(tiler() + " extract " + ana + " --zoom " + z + " --layer flow_accumulation -o " + acc,
          dir.path());
  ASSERT_EQ(e.exit_code, 0) << e.err;
  const Raster ours = read_raster(acc), peer = grass_accumulation(dir, dem);
  ASSERT_EQ(ours.width, peer.width);
  ASSERT_EQ(ours.height, peer.height);
  const bool geographic = std::string(GetParam().tiling) == "geodetic";
  auto cell_area = [&](int y) {
    return geographic ? ellipsoid_cell_area(ours.gt[3] + (y + 0.5) * ours.gt[5], ours.gt[1])
                      : ours.gt[1] * -ours.gt[5];
  };
  const int w = ours.width, h = ours.height;
  std::vector<uint8_t> our_stream(size_t(w) * h, 0), peer_stream(size_t(w) * h, 0);
  size_t best_ours = 0, best_peer = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      const double o = ours.data[i] / cell_area(y), p = std::abs(peer.data[i]);
      our_stream[i] = o >= GetParam().stream_cells;
      peer_stream[i] = p >= GetParam().stream_cells;
      if (!std::isnan(o) && (std::isnan(ours.data[best_ours]) ||
                             o > ours.data[best_ours] / cell_area(int(best_ours / w))))
        best_ours = i;
      if (!std::isnan(p) &&
          (std::isnan(peer.data[best_peer]) || p > std::abs(peer.data[best_peer])))
        best_peer = i;
    }
  auto matched = [&](const std::vector<uint8_t>& from, const std::vector<uint8_t>& in,
                     size_t& total) {
    size_t hit = 0;
    total = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        if (!from[size_t(y) * w + x]) continue;
        ++total;
        bool near = false;
        for (int dy = -1; dy <= 1 && !near; ++dy)
          for (int dx = -1; dx <= 1 && !near; ++dx) {
            const int nx = x + dx, ny = y + dy;
            near = nx >= 0 && ny >= 0 && nx < w && ny < h && in[size_t(ny) * w + nx];
          }
        hit += near;
      }
    return hit;
  };
  size_t peer_total = 0, ours_total = 0;
  const size_t peer_hit = matched(peer_stream, our_stream, peer_total);
  const size_t ours_hit = matched(our_stream, peer_stream, ours_total);
  const double peer_cells = std::abs(peer.data[best_peer]);
  const double our_cells = ours.data[best_ours] / cell_area(int(best_ours / w));
  std::printf(
      "%s: GRASS stream cells %zu, %.2f %% with ours within one cell; ours %zu, %.2f %% with "
      "GRASS's near; largest basin: GRASS (%zu, %zu) %.0f cells, ours (%zu, %zu) %.0f cells\n",
      GetParam().name, peer_total, 100.0 * peer_hit / peer_total, ours_total,
      100.0 * ours_hit / ours_total, best_peer % w, best_peer / w, peer_cells, best_ours % w,
      best_ours / w, our_cells);
  EXPECT_GT(peer_total, 500u);
  EXPECT_GE(double(peer_hit), GetParam().peer_share * double(peer_total));
  EXPECT_GE(double(ours_hit), GetParam().our_share * double(ours_total));
  if (GetParam().basin_tolerance == 0) return;
  EXPECT_LE(std::abs(int(best_ours % w) - int(best_peer % w)), 1);
  EXPECT_LE(std::abs(int(best_ours / w) - int(best_peer / w)), 1);
  EXPECT_NEAR(our_cells, peer_cells, GetParam().basin_tolerance * peer_cells);
}

// South America from etopo20 (20' pixel-is-area samples from 20 E: its
// columns 774..917 are 82 W..34 W, moved to those longitudes), with its
// coasts' sea floor; the same in an Albers equal-area projection at 20 km
// (GRASS measures the search's distances in map units, degrees in a
// geographic location, where ours are true ground distances: there the
// diagonal rule differs between the two, docs/analysis.md); and its
// lowlands (Amazon, Pantanal, Chaco: 76 W..52 W, 2 N..28 S, no sea).
constexpr const char* kSouthAmerica =
    "gdal_translate -q -srcwin 774 231 144 207 -a_ullr -82 13 -34 -56 {in} {out}";
constexpr const char* kSouthAmericaAlbers =
    "gdal_translate -q -srcwin 774 231 144 207 -a_ullr -82 13 -34 -56 {in} {dir}/sa.tif && "
    "gdalwarp -q -t_srs '+proj=aea +lat_1=-5 +lat_2=-42 +lat_0=-32 +lon_0=-60 +datum=WGS84 "
    "+units=m +no_defs' -tr 20000 20000 -r bilinear {dir}/sa.tif {out}";
constexpr const char* kLowlands =
    "gdal_translate -q -srcwin 792 264 72 90 -a_ullr -76 2 -52 -28 {in} {out}";

// Measured (GRASS's stream cells with ours within one cell / ours with
// GRASS's near), fill then carve: brasilia 98.9 / 87.7 %, 99.9 / 90.0 %;
// jacksboro 99.97 / 99.5 %, 99.9 / 99.5 %; South America 90.9 / 91.3 %,
// 96.0 / 95.7 %; in Albers 97.4 / 96.6 %, 100 / 99.5 %; the lowlands
// 88.7 / 88.7 %, 100 / 99.2 % (docs/analysis.md, "Flow methods").
INSTANTIATE_TEST_SUITE_P(
    Samples, FlowVsGrass,
    ::testing::Values(
        GrassCase{"brasilia", "brasilia.tif", "local", "fill", "", 1000, 0.04, 0.96, 0.85},
        GrassCase{"jacksboro", "jacksboro.tif", "geodetic", "fill", "", 1000, 0.04, 0.96, 0.96},
        GrassCase{"brasilia_carve", "brasilia.tif", "local", "carve", "", 1000, 0.04, 0.99, 0.88},
        GrassCase{"jacksboro_carve", "jacksboro.tif", "geodetic", "carve", "", 1000, 0.04, 0.99,
                  0.99},
        GrassCase{"south_america", "etopo20.tif", "geodetic", "fill", kSouthAmerica, 1000, 0, 0.90,
                  0.90},
        GrassCase{"south_america_carve", "etopo20.tif", "geodetic", "carve", kSouthAmerica, 1000, 0,
                  0.95, 0.95},
        GrassCase{"south_america_albers", "etopo20.tif", "local", "fill", kSouthAmericaAlbers, 1000,
                  0.04, 0.96, 0.95},
        GrassCase{"south_america_albers_carve", "etopo20.tif", "local", "carve",
                  kSouthAmericaAlbers, 1000, 0.04, 0.99, 0.98},
        GrassCase{"lowlands", "etopo20.tif", "geodetic", "fill", kLowlands, 300, 0.04, 0.87, 0.87},
        GrassCase{"lowlands_carve", "etopo20.tif", "geodetic", "carve", kLowlands, 300, 0.04, 0.99,
                  0.98}),
    [](const auto& info) { return std::string(info.param.name); });

// Every layer of every zoom, extracted, equal sample for sample.
void expect_same_layers(const TempDir& dir, const std::string& a, const std::string& b,
                        int max_zoom) {
  for (int z = 0; z <= max_zoom; ++z)
    for (const std::string layer : {"flow_direction", "flow_accumulation"}) {
      const std::string ta = (dir / ("a_" + layer + ".tif")).string(),
                        tb = (dir / ("b_" + layer + ".tif")).string();
      const std::string zs = std::to_string(z);
      ASSERT_EQ(run(tiler() + " extract --force " + a + " --zoom " + zs + " --layer " + layer +
                        " -o " + ta,
                    dir.path())
                    .exit_code,
                0);
      ASSERT_EQ(run(tiler() + " extract --force " + b + " --zoom " + zs + " --layer " + layer +
                        " -o " + tb,
                    dir.path())
                    .exit_code,
                0);
      const Raster ra = read_raster(ta), rb = read_raster(tb);
      ASSERT_EQ(ra.data.size(), rb.data.size());
      size_t differ = 0;
      for (size_t i = 0; i < ra.data.size(); ++i)
        differ += !(ra.data[i] == rb.data[i] || (std::isnan(ra.data[i]) && std::isnan(rb.data[i])));
      EXPECT_EQ(differ, 0u) << layer << " zoom " << z;
    }
}

int chunks_in(const std::string& stderr_text) {
  return static_cast<int>(integer_after(stderr_text, " cells in "));
}

// brasilia in 64 chunks (--memory-mb 1, scratch on disk) and in 4 (scratch
// in memory) against one chunk: the same samples at every zoom, and the same
// bytes for 1 and 2 threads.
TEST(FlowOutOfCore, EqualsTheInMemorySolve) {
  TempDir dir;
  const std::string pkg = (dir / "t.mbtiles").string();
  ASSERT_TRUE(build_terrain("--tiling local", sample("brasilia.tif").string(), pkg, dir.path()));
  const std::string whole = (dir / "whole.mbtiles").string(), ooc = (dir / "ooc.mbtiles").string();
  const RunResult a = run(tiler() + " analyze --layers flow " + pkg + " -o " + whole, dir.path());
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_EQ(chunks_in(a.err), 1) << a.err;
  // The same output path (it is in the recorded command line), one thread
  // count after the other.
  std::string bytes[2];
  for (int j = 1; j <= 2; ++j) {
    const RunResult b = run(tiler() + " analyze --force --layers flow --memory-mb 1 -j " +
                                std::to_string(j) + " " + pkg + " -o " + ooc,
                            dir.path());
    ASSERT_EQ(b.exit_code, 0) << b.err;
    EXPECT_GE(chunks_in(b.err), 16) << b.err;
    EXPECT_NE(b.err.find("(scratch on disk)"), std::string::npos) << b.err;
    bytes[j - 1] = read_file(ooc);
  }
  EXPECT_TRUE(bytes[0] == bytes[1]) << "-j 1 and -j 2 differ";
  expect_same_layers(dir, whole, ooc, 1);
  // Several chunks (--flow-chunk) whose scratch fits the default budget
  // beside them: kept in memory. Neither option is in the recorded command
  // line (they cannot change the output): the same bytes again.
  const RunResult c =
      run(tiler() + " analyze --force --layers flow --flow-chunk 256 -j 2 " + pkg + " -o " + ooc,
          dir.path());
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_EQ(chunks_in(c.err), 4) << c.err;
  EXPECT_NE(c.err.find("(scratch in memory)"), std::string::npos) << c.err;
  EXPECT_TRUE(read_file(ooc) == bytes[0]) << "--flow-chunk 256 and --memory-mb 1 differ";
}

// Carve gives the same bytes for 1 and 2 threads and any chunking of the
// pyramid (--flow-chunk), and differs from fill.
TEST(FlowCarve, SameBytesForAnyThreadsAndChunks) {
  TempDir dir;
  const std::string pkg = (dir / "t.mbtiles").string(), out = (dir / "c.mbtiles").string(),
                    fill = (dir / "f.mbtiles").string();
  ASSERT_TRUE(build_terrain("--tiling local", sample("brasilia.tif").string(), pkg, dir.path()));
  std::string bytes[3];
  const char* options[3] = {"-j 1", "-j 2", "-j 2 --flow-chunk 64"};
  for (int k = 0; k < 3; ++k) {
    const RunResult r = run(tiler() + " analyze --force --layers flow --flow-method carve " +
                                options[k] + " " + pkg + " -o " + out,
                            dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("routed by least cost in memory (--flow-method carve)"), std::string::npos)
        << r.err;
    bytes[k] = read_file(out);
  }
  EXPECT_TRUE(bytes[0] == bytes[1]) << "-j 1 and -j 2 differ";
  EXPECT_TRUE(bytes[0] == bytes[2]) << "--flow-chunk 64 differs";
  const RunResult info = run(tiler() + " info " + out, dir.path());
  EXPECT_NE(info.out.find("carve"), std::string::npos) << info.out;
  ASSERT_EQ(run(tiler() + " analyze -q --layers flow " + pkg + " -o " + fill, dir.path()).exit_code,
            0);
  EXPECT_NE(run(tiler() + " info " + fill, dir.path()).out.find("fill"), std::string::npos);
  EXPECT_FALSE(read_file(fill) == bytes[0]) << "carve and fill gave the same package";
}

// All water leaves through outlets: the outlets' upstream areas add up to
// the area of every cell (within the layer's 0.035 % quantum).
TEST(FlowOutOfCore, ConservesWater) {
  TempDir dir;
  const std::string pkg = (dir / "t.mbtiles").string(), ana = (dir / "a.mbtiles").string();
  ASSERT_TRUE(build_terrain("--tiling local", sample("brasilia.tif").string(), pkg, dir.path()));
  ASSERT_EQ(
      run(tiler() + " analyze -q --layers flow --memory-mb 1 " + pkg + " -o " + ana, dir.path())
          .exit_code,
      0);
  const std::string dir_tif = (dir / "d.tif").string(), acc_tif = (dir / "acc.tif").string();
  ASSERT_EQ(run(tiler() + " extract " + ana + " --zoom 1 --layer flow_direction -o " + dir_tif,
                dir.path())
                .exit_code,
            0);
  ASSERT_EQ(run(tiler() + " extract " + ana + " --zoom 1 --layer flow_accumulation -o " + acc_tif,
                dir.path())
                .exit_code,
            0);
  const Raster d = read_raster(dir_tif), acc = read_raster(acc_tif);
  double outlets = 0;
  size_t cells = 0, outlet_count = 0;
  for (size_t i = 0; i < d.data.size(); ++i) {
    if (std::isnan(d.data[i])) continue;
    ++cells;
    if (d.data[i] == 0) {
      outlets += acc.data[i];
      ++outlet_count;
    }
  }
  const double total = double(cells) * d.gt[1] * -d.gt[5];
  std::printf("%zu cells, %zu outlets: outlets drain %.6g m^2 of %.6g m^2\n", cells, outlet_count,
              outlets, total);
  EXPECT_GT(cells, 100000u);
  EXPECT_NEAR(outlets, total, 0.0004 * total);
}

// Peak memory (the kernel's maximum resident set) of one command, in MB.
double peak_rss_mb(const std::string& command, const fs::path& dir) {
  const std::string out = (dir / "rss.txt").string();
  const RunResult r = run("/usr/bin/time -f %M -o " + out + " " + command, dir);
  EXPECT_EQ(r.exit_code, 0) << command << "\n" << r.err;
  return std::stod(read_file(out)) / 1024;
}

// A 2049^2 DEM (hills and closed hollows on a tilted plane) whose working
// set in one chunk would be about 200 MB (48 bytes a cell): with
// --memory-mb 24 the peak stays within the budget plus the process's fixed
// overhead (stated as 40 MB: 36 MB is the tool with GDAL and PROJ loaded,
// doing nothing), and the answer equals the default budget's.
TEST(FlowOutOfCore, PeakMemoryStaysWithinTheBudget) {
#ifdef GLOBE_ADDRESS_SANITIZER
  GTEST_SKIP() << "AddressSanitizer's shadow memory and quarantine are not the tool's";
#endif
  TempDir dir;
  const double gt[6] = {500000, 10, 0, 4000000, 0, -10};
  const std::string src = (dir / "hills.tif").string(), pkg = (dir / "t.mbtiles").string();
  write_dem(src, 2049, 2049, gt, "EPSG:32632", GDT_Float32, [](int x, int y) {
    return 800 - 0.05 * x - 0.03 * y + 40 * std::sin(x * 0.021) * std::cos(y * 0.017) +
           15 * std::sin((x + 2 * y) * 0.073);
  });
  ASSERT_TRUE(build_terrain("--tiling local", src, pkg, dir.path()));
  const std::string whole = (dir / "whole.mbtiles").string(), ooc = (dir / "ooc.mbtiles").string();
  const double default_budget =
      peak_rss_mb(tiler() + " analyze -q --layers flow " + pkg + " -o " + whole, dir.path());
  const double budget = 24;
  const double out_of_core = peak_rss_mb(
      tiler() + " analyze -q --layers flow --memory-mb 24 " + pkg + " -o " + ooc, dir.path());
  std::printf("peak RSS: default budget %.0f MB, --memory-mb %.0f: %.0f MB\n", default_budget,
              budget, out_of_core);
  EXPECT_LT(out_of_core, budget + 40);
  expect_same_layers(dir, whole, ooc, 3);
}

struct Extent {
  const char* name;
  double west, north;  // a 2 x 2 degree DEM of 0.01 degree pixels
  bool east;           // falls eastwards (else southwards)
  std::vector<std::string> bboxes;
  // analyze's flow options: fill out of core in the least memory; carve
  // (its window in memory) across the antimeridian
  const char* flow_options;
};

void PrintTo(const Extent& e, std::ostream* os) {
  *os << e.name;
}

class FlowGeodetic : public ::testing::TestWithParam<Extent> {};

// A tilted plane: all water runs straight down the slope, so a cell's
// upstream area is the sum of the areas of the cells above it in its row
// (east) or column (south), counted here from the extracted grid.
TEST_P(FlowGeodetic, UpstreamAreasOfAPlane) {
  const Extent& ex = GetParam();
  TempDir dir;
  const double gt[6] = {ex.west, 0.01, 0, ex.north, 0, -0.01};
  const std::string src = (dir / "plane.tif").string(), pkg = (dir / "t.mbtiles").string(),
                    ana = (dir / "a.mbtiles").string();
  write_dem(src, 200, 200, gt, "EPSG:4326", GDT_Float32,
            [&](int x, int y) { return ex.east ? 2000 - 5.0 * x : 2000 - 5.0 * y; });
  ASSERT_TRUE(build_terrain("--tiling geodetic --max-zoom 8", src, pkg, dir.path()));
  const RunResult a =
      run(tiler() + " analyze -q --layers flow " + ex.flow_options + " " + pkg + " -o " + ana,
          dir.path());
  ASSERT_EQ(a.exit_code, 0) << a.err;
  std::vector<Raster> parts;
  for (const std::string& bbox : ex.bboxes) {
    const std::string out = (dir / ("acc" + std::to_string(parts.size()) + ".tif")).string();
    const RunResult e = run(tiler() + " extract " + ana + " --zoom 8 --layer flow_accumulation" +
                                (bbox.empty() ? "" : " --bbox=" + bbox) + " -o " + out,
                            dir.path());
    ASSERT_EQ(e.exit_code, 0) << e.err;
    parts.push_back(read_raster(out));
  }
  const double sp = parts[0].gt[1];
  size_t checked = 0, across = 0;
  double worst = 0;
  if (ex.east) {
    // Parts west to east with the same rows; a column at exactly 180 degrees
    // east is the one at 180 west. The data's edge samples are level
    // (bilinear at the edge), so counting starts 0.05 degrees inside: from
    // there each sample adds one cell.
    for (int y = 0; y < parts[0].height; ++y) {
      const double lat = parts[0].gt[3] + (y + 0.5) * parts[0].gt[5];
      if (lat > ex.north - 0.05 || lat < ex.north - 2 + 0.05) continue;
      const double cell = ellipsoid_cell_area(lat, sp);
      double base = -1;
      int cells = 0;
      for (size_t p = 0; p < parts.size(); ++p) {
        const Raster& r = parts[p];
        for (int x = 0; x < r.width; ++x) {
          const double lon = r.gt[0] + (x + 0.5) * r.gt[1];
          if (p == 0 && parts.size() > 1 && lon > 180 - sp / 2) continue;
          const double v = r.at(x, y);
          if (std::isnan(v) || (p == 0 && lon < ex.west + 0.05)) continue;
          if (base < 0) {
            base = v;
            continue;
          }
          const double want = base + ++cells * cell;
          worst = std::max(worst, std::abs(v - want) / want);
          ++checked;
          across += p > 0;
        }
      }
    }
  } else {
    const Raster& r = parts[0];
    for (int x = 0; x < r.width; ++x) {
      const double lon = r.gt[0] + (x + 0.5) * r.gt[1];
      double want = 0;
      for (int y = 0; y < r.height; ++y) {
        const double v = r.at(x, y);
        if (std::isnan(v)) continue;
        want += ellipsoid_cell_area(r.gt[3] + (y + 0.5) * r.gt[5], sp);
        if (lon < ex.west + 0.05 || lon > ex.west + 2 - 0.05) continue;
        worst = std::max(worst, std::abs(v - want) / want);
        ++checked;
      }
    }
  }
  std::printf("%s: %zu samples (%zu east of the antimeridian), worst relative error %.5f\n",
              ex.name, checked, across, worst);
  EXPECT_GT(checked, 10000u);
  if (ex.bboxes.size() > 1) {
    EXPECT_GT(across, 1000u);
  }
  EXPECT_LT(worst, 0.002);
}

INSTANTIATE_TEST_SUITE_P(
    Extents, FlowGeodetic,
    ::testing::Values(
        Extent{"south_88n", 10, 89, false, {""}, "--memory-mb 1"},
        Extent{
            "east_antimeridian", 179, 1, true, {"179,-1,180,1", "-180,-1,-179,1"}, "--memory-mb 1"},
        Extent{"south_88n_carve", 10, 89, false, {""}, "--flow-method carve"},
        Extent{"east_antimeridian_carve",
               179,
               1,
               true,
               {"179,-1,180,1", "-180,-1,-179,1"},
               "--flow-method carve"}),
    [](const auto& info) { return std::string(info.param.name); });

// The whole world (etopo20 on the web-mercator tiling, which wraps east-west
// and ends at 85 degrees): water leaves only through the first and last rows
// - the 180-degree columns are interior, so no outlet lies on them - and the
// outlets drain the area of every cell, each cell's area summed here from its
// mercator row's latitudes on the ellipsoid. Both methods (carve's window
// is the whole width, wrapping).
class FlowGlobal : public ::testing::TestWithParam<const char*> {};

TEST_P(FlowGlobal, TheWholeWorldDrainsOnlyAtItsPolarRowsAndConservesWater) {
  TempDir dir;
  const std::string pkg = (dir / "t.mbtiles").string(), ana = (dir / "a.mbtiles").string();
  ASSERT_TRUE(build_terrain("--max-zoom 3", sample("etopo20.tif").string(), pkg, dir.path()));
  ASSERT_EQ(run(tiler() + " analyze -q --layers flow --flow-method " + GetParam() + " " + pkg +
                    " -o " + ana,
                dir.path())
                .exit_code,
            0);
  const std::string d_tif = (dir / "d.tif").string(), a_tif = (dir / "acc.tif").string();
  ASSERT_EQ(
      run(tiler() + " extract " + ana + " --zoom 3 --layer flow_direction -o " + d_tif, dir.path())
          .exit_code,
      0);
  ASSERT_EQ(run(tiler() + " extract " + ana + " --zoom 3 --layer flow_accumulation -o " + a_tif,
                dir.path())
                .exit_code,
            0);
  const Raster d = read_raster(d_tif), acc = read_raster(a_tif);
  // The extract's last column repeats the first (180 degrees east = west).
  const int w = d.width - 1, h = d.height;
  ASSERT_NEAR(d.gt[0] + (w + 0.5) * d.gt[1], -(d.gt[0] + 0.5 * d.gt[1]), d.gt[1] / 2)
      << "a whole-world extract expected (sample columns at -180 and +180 degrees)";
  const double r = 6378137.0;
  auto lat = [&](double y) {
    return (2 * std::atan(std::exp(y / r)) - std::numbers::pi / 2) / kDeg;
  };
  size_t outlets = 0, off_polar_rows = 0, cells = 0;
  double drained = 0, total = 0;
  for (int y = 0; y < h; ++y) {
    const double top = d.gt[3] + y * d.gt[5];  // pixel edges: the cell around the sample
    const double cell = ellipsoid_zone_area(lat(top), lat(top + d.gt[5]), d.gt[1] / r / kDeg);
    for (int x = 0; x < w; ++x) {
      if (std::isnan(d.at(x, y))) continue;
      ++cells;
      total += cell;
      if (d.at(x, y) != 0) continue;
      ++outlets;
      drained += acc.at(x, y);
      if (y != 0 && y != h - 1) ++off_polar_rows;
    }
  }
  std::printf(
      "whole world: %zu cells, %zu outlets (%zu off the polar rows), drained %.6g of %.6g m^2\n",
      cells, outlets, off_polar_rows, drained, total);
  EXPECT_EQ(cells, size_t(w) * h);
  EXPECT_GT(outlets, 100u);
  EXPECT_EQ(off_polar_rows, 0u);
  EXPECT_NEAR(drained, total, 0.0004 * total);
}

INSTANTIATE_TEST_SUITE_P(Methods, FlowGlobal, ::testing::Values("fill", "carve"),
                         [](const auto& info) { return std::string(info.param); });

TEST(FlowErrors, BadMemoryBudget) {
  TempDir dir;
  const RunResult r =
      run(tiler() + " analyze --layers flow --memory-mb 0 x.mbtiles -o a.mbtiles", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--memory-mb"), std::string::npos) << r.err;
}

TEST(FlowErrors, BadChunkSide) {
  TempDir dir;
  for (const char* side : {"100", "32", "x"}) {
    const RunResult r =
        run(tiler() + " analyze --layers flow --flow-chunk " + side + " x.mbtiles -o a.mbtiles",
            dir.path());
    EXPECT_EQ(r.exit_code, 2) << side;
    EXPECT_NE(r.err.find("--flow-chunk"), std::string::npos) << r.err;
  }
}

TEST(FlowErrors, BadFlowMethod) {
  TempDir dir;
  const RunResult r = run(
      tiler() + " analyze --layers flow --flow-method breach x.mbtiles -o a.mbtiles", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--flow-method: give fill or carve, not 'breach'"), std::string::npos)
      << r.err;
}

// Carve holds the data's window in memory: a budget below it is refused
// with the size it needs, naming the package, and no output is left; fill
// solves the same package within that budget.
TEST(FlowErrors, CarveBeyondTheMemoryBudgetIsRefused) {
  TempDir dir;
  const std::string pkg = (dir / "t.mbtiles").string(), ana = (dir / "a.mbtiles").string();
  ASSERT_TRUE(build_terrain("--tiling local", sample("brasilia.tif").string(), pkg, dir.path()));
  const RunResult r = run(
      tiler() + " analyze -q --layers flow --flow-method carve --memory-mb 2 " + pkg + " -o " + ana,
      dir.path());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--flow-method carve holds the data's part of the finest zoom of " + pkg),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("cells need about 7 MB, more than --memory-mb 2"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(ana));
  for (const auto& e : fs::directory_iterator(dir.path()))
    EXPECT_EQ(e.path().filename().string().rfind("a.mbtiles", 0), std::string::npos)
        << "left behind: " << e.path();
  EXPECT_EQ(
      run(tiler() + " analyze -q --layers flow --memory-mb 2 " + pkg + " -o " + ana, dir.path())
          .exit_code,
      0);
}

}  // namespace
