// `globe-vectorize points` on synthetic CSV places (docs/points.md): the
// aggregation conserves totals and source places at every zoom, a merged
// place is the weighted centre of its places with their sums (or means), a
// place survives the round trip through `extract`, the antimeridian and the
// poles, determinism, and bad input. The references are the inputs, summed
// and weighed here, and GDAL's own reading of the extracts.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "line_fixtures.hpp"
#include "point_fixtures.hpp"
#include "test_support.hpp"

using namespace globe_test;

namespace {

constexpr double kR = 6378137.0;  // web mercator sphere
double merc_x(double lon) {
  return kR * lon * std::numbers::pi / 180;
}
double merc_y(double lat) {
  return kR * std::log(std::tan(std::numbers::pi / 4 + lat * std::numbers::pi / 360));
}

std::vector<CsvPlace> random_places(int n, uint32_t seed, int fields) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> lon(-10, 30), lat(35, 60);
  std::vector<CsvPlace> out;
  for (int i = 0; i < n; ++i) {
    CsvPlace p{"p" + std::to_string(i), lon(rng), lat(rng), {}};
    for (int f = 0; f < fields; ++f)
      p.values.push_back(double(rng() % 1001));  // integers: float32 sums stay exact
    out.push_back(p);
  }
  return out;
}

class PointsCli : public ::testing::Test {
 protected:
  // Builds `csv` with `options`; asserts success.
  void build(const std::string& csv, const std::string& options, const std::string& out) {
    const RunResult r = run(
        vectorize() + " points -q " + csv + " --xy lon,lat -o " + out + " " + options, dir_.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  std::vector<ExtractedPlace> extract(const std::string& pkg, int z,
                                      const std::vector<std::string>& fields) {
    const std::string out = (dir_ / ("z" + std::to_string(z) + ".gpkg")).string();
    const RunResult r = run(
        vectorize() + " extract --force -q " + pkg + " --zoom " + std::to_string(z) + " -o " + out,
        dir_.path());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return read_places(out, fields);
  }
  TempDir dir_;
};

}  // namespace

// Every zoom: the places stand for every source place once, and their
// values sum to the inputs' totals (integers, so exactly).
TEST_F(PointsCli, AggregationConservesTotalsAndPlacesAtEveryZoom) {
  const std::vector<std::string> fields{"a", "b", "c"};
  const auto places = random_places(2000, 1, 3);
  const std::string csv = (dir_ / "p.csv").string(), pkg = (dir_ / "p.mbtiles").string();
  write_places_csv(csv, fields, places);
  build(csv, "--fields a,b,c --max-zoom 8", pkg);
  std::vector<double> totals(3, 0);
  for (const CsvPlace& p : places)
    for (int f = 0; f < 3; ++f)
      totals[f] += p.values[f];
  std::vector<size_t> counts;
  for (int z = 0; z <= 8; ++z) {
    const auto got = extract(pkg, z, fields);
    std::vector<double> sums(3, 0);
    int64_t sources = 0;
    for (const ExtractedPlace& p : got) {
      sources += p.places;
      for (int f = 0; f < 3; ++f)
        sums[f] += p.values[f];
    }
    EXPECT_EQ(sources, 2000) << "zoom " << z;
    for (int f = 0; f < 3; ++f)
      EXPECT_EQ(sums[f], totals[f]) << "zoom " << z << " field " << fields[f];
    counts.push_back(got.size());
  }
  for (int z = 0; z < 8; ++z)
    EXPECT_LE(counts[z], counts[z + 1]) << "zoom " << z << " has more places than zoom " << z + 1;
  EXPECT_LT(counts[0], 40u);
  EXPECT_GT(counts[8], 1500u);
  const RunResult v = run(vectorize() + " validate " + pkg, dir_.path());
  EXPECT_EQ(v.exit_code, 0) << v.out;
}

// Two groups of places a few hundred metres apart and a lone place, far
// from each other: at zoom 5 (40 px = 1.8 degrees) each group is one place
// with the smallest id, the count, the sums, and the centre weighted by the
// sum of the values (in the tiling's metres), within one tile unit.
TEST_F(PointsCli, AMergedPlaceIsTheWeightedCentreOfItsPlacesWithTheirSums) {
  const std::vector<std::string> fields{"x", "y"};
  const std::vector<CsvPlace> places{
      {"a1", 10.000, 50.000, {1, 2}},    {"a2", 10.004, 50.003, {30, 0}},
      {"a3", 9.997, 50.001, {4, 4}},     {"b1", -60.0, -20.0, {5, 5}},
      {"b2", -60.002, -20.001, {0, 15}}, {"c", 100, 30, {7, 1}}};
  const std::string csv = (dir_ / "p.csv").string(), pkg = (dir_ / "p.mbtiles").string();
  write_places_csv(csv, fields, places);
  build(csv, "--fields x,y --max-zoom 7", pkg);
  const auto got = extract(pkg, 5, fields);
  ASSERT_EQ(got.size(), 3u);
  auto expect_group = [&](size_t first, size_t n) {
    double wx = 0, wy = 0, w = 0, s0 = 0, s1 = 0;
    for (size_t i = first; i < first + n; ++i) {
      const double wi = std::abs(places[i].values[0]) + std::abs(places[i].values[1]);
      wx += wi * merc_x(places[i].lon);
      wy += wi * merc_y(places[i].lat);
      w += wi;
      s0 += places[i].values[0];
      s1 += places[i].values[1];
    }
    const ExtractedPlace* p = nullptr;
    for (const ExtractedPlace& e : got)
      if (e.id == int64_t(first + 1)) p = &e;
    ASSERT_NE(p, nullptr) << "no place with id " << first + 1;
    EXPECT_EQ(p->places, int64_t(n));
    EXPECT_EQ(p->values, (std::vector<double>{s0, s1}));
    const double unit = 2 * std::numbers::pi * kR / 32 / 4096;
    EXPECT_NEAR(p->x, wx / w, unit);
    EXPECT_NEAR(p->y, wy / w, unit);
  };
  expect_group(0, 3);
  expect_group(3, 2);
  expect_group(5, 1);
}

// --merge-px 0: the finest zoom holds every place, with its values (float32)
// and its position within one tile unit; its attributes stay in the
// features table.
TEST_F(PointsCli, EveryPlaceSurvivesTheRoundTripThroughExtract) {
  const std::vector<std::string> fields{"u", "v"};
  std::vector<CsvPlace> places = random_places(500, 2, 2);
  for (size_t i = 0; i < places.size(); ++i)
    places[i].values = {i * 0.375, 1e6 / (i + 1.0)};
  const std::string csv = (dir_ / "p.csv").string(), pkg = (dir_ / "p.mbtiles").string();
  write_places_csv(csv, fields, places);
  build(csv, "--fields u,v --merge-px 0 --max-zoom 10 --label-field name", pkg);
  const auto got = extract(pkg, 10, fields);
  ASSERT_EQ(got.size(), places.size());
  const double unit = 2 * std::numbers::pi * kR / 1024 / 4096;
  for (const ExtractedPlace& e : got) {
    ASSERT_GE(e.id, 1);
    ASSERT_LE(e.id, int64_t(places.size()));
    const CsvPlace& p = places[e.id - 1];  // ids follow the input order
    EXPECT_EQ(e.places, 1);
    EXPECT_NE(e.properties.find("\"name\":\"" + p.name + "\""), std::string::npos) << e.properties;
    EXPECT_EQ(e.values[0], double(float(p.values[0])));
    EXPECT_EQ(e.values[1], double(float(p.values[1])));
    EXPECT_NEAR(e.x, merc_x(p.lon), unit);
    EXPECT_NEAR(e.y, merc_y(p.lat), unit);
  }
}

// --aggregate mean: a merged place shows the means of its places; times
// their counts they sum to the inputs' totals.
TEST_F(PointsCli, MeansTimesCountsSumToTheTotals) {
  const std::vector<std::string> fields{"m"};
  const auto places = random_places(800, 3, 1);
  const std::string csv = (dir_ / "p.csv").string(), pkg = (dir_ / "p.mbtiles").string();
  write_places_csv(csv, fields, places);
  build(csv, "--fields m --aggregate mean --max-zoom 6", pkg);
  double total = 0;
  for (const CsvPlace& p : places)
    total += p.values[0];
  for (int z : {0, 3, 6}) {
    double sum = 0;
    for (const ExtractedPlace& e : extract(pkg, z, fields)) {
      EXPECT_GE(e.values[0], 0);
      EXPECT_LE(e.values[0], 1000);
      sum += e.values[0] * double(e.places);
    }
    EXPECT_NEAR(sum, total, 1e-5 * total) << "zoom " << z;
  }
}

// Places 0.4 degree apart across the antimeridian are neighbours: at a
// coarse zoom they are one place next to 180 degrees, in both global
// tilings. Places next to the poles: kept by the geodetic tiling, at the
// web mercator limit (85.05 degrees) by web mercator.
TEST_F(PointsCli, TheAntimeridianJoinsNeighboursAndThePolesAreKept) {
  const std::vector<std::string> fields{"n"};
  const std::vector<CsvPlace> places{{"east", 179.8, 10, {1}},
                                     {"west", -179.8, 10.01, {3}},
                                     {"pole1", 20, 89.5, {2}},
                                     {"pole2", 22, 89.6, {2}}};
  const std::string csv = (dir_ / "p.csv").string();
  write_places_csv(csv, fields, places);
  for (const char* tiling : {"webmercator", "geodetic"}) {
    const std::string pkg = (dir_ / (std::string(tiling) + ".mbtiles")).string();
    build(csv, std::string("--fields n --max-zoom 9 --tiling ") + tiling, pkg);
    const auto got = extract(pkg, 2, fields);
    const ExtractedPlace* seam = nullptr;
    for (const ExtractedPlace& e : got)
      if (e.id == 1) seam = &e;
    ASSERT_NE(seam, nullptr) << tiling;
    EXPECT_EQ(seam->places, 2) << tiling;
    EXPECT_EQ(seam->values[0], 4) << tiling;
    // East 179.8 weighing 1, west -179.8 weighing 3: -179.9, across the seam.
    EXPECT_NEAR(seam->lon, -179.9, 0.02) << tiling << ": the centre crossed the map instead";
    const auto fine = extract(pkg, 9, fields);
    EXPECT_EQ(fine.size(), 4u) << tiling;
    for (const ExtractedPlace& e : fine) {
      if (e.id < 3) continue;
      const double lat = std::string(tiling) == "geodetic" ? (e.id == 3 ? 89.5 : 89.6) : 85.0511;
      EXPECT_NEAR(e.lat, lat, 0.01) << tiling << " place " << e.id;
    }
  }
}

// -j1 with the default memory against -j2 with 1 MB, where every sort
// spills to run files: the same bytes.
TEST_F(PointsCli, OutputIsTheSameForAnyThreadCountAndMemory) {
  const auto places = random_places(15000, 4, 4);
  const std::string csv = (dir_ / "p.csv").string();
  write_places_csv(csv, {"a", "b", "c", "d"}, places);
  for (const char* j : {"1", "2"}) {
    fs::create_directories(dir_ / j);
    const RunResult r = run("cd " + (dir_ / j).string() + " && " + vectorize() + " points -q " +
                                csv + " --xy lon,lat --fields a,b,c,d -o p.mbtiles -j" + j +
                                (std::string(j) == "2" ? " --memory-mb 1" : ""),
                            dir_.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / j / "p.mbtiles.scratch-places")) << "scratch file left behind";
  }
  const bool same = read_file(dir_ / "1" / "p.mbtiles") == read_file(dir_ / "2" / "p.mbtiles");
  EXPECT_TRUE(same) << "-j1 and -j2 --memory-mb 1 packages differ";
}

TEST_F(PointsCli, BadInputIsAClearErrorAndWritesNothing) {
  const std::string csv = (dir_ / "p.csv").string();
  write_places_csv(csv, {"a", "b"}, {{"x", 1, 2, {3, 4}}, {"y", 2, 3, {5, -6}}});
  const std::string text = (dir_ / "text.csv").string();
  write_text(text, "name,lon,lat,a\nx,1,2,many\n");
  const std::string nocoords = (dir_ / "nocoords.csv").string();
  write_text(nocoords, "name,a\nx,1\n");
  const std::string roads = sample("canada_roads.shp").string() + " --s_srs EPSG:3978";
  auto expect_error = [&](const std::string& args, int code, const std::string& says) {
    const RunResult r = run(
        vectorize() + " points " + args + " -o " + (dir_ / "out.mbtiles").string(), dir_.path());
    EXPECT_EQ(r.exit_code, code) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << args << "\n" << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "out.mbtiles")) << args;
    EXPECT_FALSE(fs::exists(dir_ / "out.mbtiles.tmp")) << args;
  };
  expect_error(csv + " --xy lon,lat --fields a,b", 1,
               "p.csv layer 'p' feature 2: b is -6, a negative value");
  expect_error(
      csv + " --xy lon,lat --fields a,nope", 2,
      "--fields 'nope': " + csv + " layer 'p' has no such field; its fields are: name, a, b");
  expect_error(csv + " --xy lon,lat --fields a,name", 2, "--fields 'name':");
  expect_error(text + " --xy lon,lat --fields a", 2, "values there, not numbers");
  expect_error(csv + " --xy lon,lat", 2, "--fields is required");
  expect_error(csv + " --xy lon,lat --fields a --label-field title", 2, "--label-field 'title'");
  expect_error(nocoords + " --xy lon,lat --fields a", 1, "no columns 'lon' and 'lat'");
  expect_error(csv + " --xy lon,lat --fields a --where \"a > 100\"", 1,
               "no place with a usable point");
  expect_error(roads + " --fields CLASS", 1, "holds lines; globe-vectorize points draws charts");
  expect_error(sample("canada_roads.shp").string() + " --xy lon,lat --fields CLASS", 1,
               "--xy reads CSV files");
  expect_error(csv + " --xy lon --fields a", 2, "--xy: expected 2 comma-separated names");
  // --signed keeps the negative value.
  const std::string signed_pkg = (dir_ / "signed.mbtiles").string();
  const RunResult ok = run(
      vectorize() + " points -q " + csv + " --xy lon,lat --fields a,b --signed -o " + signed_pkg,
      dir_.path());
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  const RunResult info = run(vectorize() + " info " + signed_pkg, dir_.path());
  EXPECT_NE(info.out.find("values signed"), std::string::npos) << info.out;
}
