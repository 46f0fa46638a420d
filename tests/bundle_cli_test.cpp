// `globe-vectorize bundle` on synthetic networks and flows (docs/bundles.md):
// routed lengths against a shortest path computed here (Dijkstra over the
// network's vertices with haversine lengths), every connection a chain of
// bundles from its origin's node to its destination's, weights conserved at
// every node, drawn bundles within their corridor of the network (read back
// through `extract` and OGR, measured here), ids joined to locations, bad
// rows counted, unrouted connections drawn straight or dropped, the
// antimeridian, determinism, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <queue>
#include <random>
#include <set>

#include "line_fixtures.hpp"
#include "test_support.hpp"
#include "tileformat/feature_table.hpp"
#include "tileformat/json.hpp"
#include "tileformat/package.hpp"

using namespace globe_test;

namespace {

struct LL {
  double lon, lat;
  bool operator<(const LL& o) const { return std::tie(lon, lat) < std::tie(o.lon, o.lat); }
  bool operator==(const LL&) const = default;
};

double haversine(LL a, LL b) {
  return haversine_m(a.lon, a.lat, b.lon, b.lat);
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6f", v);
  return buf;
}

// GeoJSON lines in lon/lat.
std::string geojson_lines(const std::vector<std::vector<LL>>& lines) {
  std::string s = "{\"type\":\"FeatureCollection\",\"features\":[";
  for (size_t i = 0; i < lines.size(); ++i) {
    s += std::string(i ? "," : "") +
         "{\"type\":\"Feature\",\"properties\":{\"n\":" + std::to_string(i) +
         "},\"geometry\":{\"type\":\"LineString\",\"coordinates\":[";
    for (size_t k = 0; k < lines[i].size(); ++k)
      s +=
          std::string(k ? "," : "") + "[" + fmt(lines[i][k].lon) + "," + fmt(lines[i][k].lat) + "]";
    s += "]}}";
  }
  return s + "]}";
}

// A road grid over 10..14 E, 45..48 N: a line every half degree each way,
// a vertex every tenth of a degree (chains for the reduction).
std::vector<std::vector<LL>> grid_lines() {
  std::vector<std::vector<LL>> lines;
  for (int j = 0; j <= 6; ++j) {
    std::vector<LL> row;
    for (int i = 0; i <= 40; ++i)
      row.push_back({10 + i / 10.0, 45 + j / 2.0});
    lines.push_back(row);
  }
  for (int i = 0; i <= 8; ++i) {
    std::vector<LL> col;
    for (int j = 0; j <= 30; ++j)
      col.push_back({10 + i / 2.0, 45 + j / 10.0});
    lines.push_back(col);
  }
  return lines;
}

// Shortest network distances from `from` (a vertex) by Dijkstra over the
// lines' vertices (rounded to 1e-6 degrees, as written).
std::map<LL, double> network_distances(const std::vector<std::vector<LL>>& lines, LL from) {
  auto key = [](LL p) { return LL{std::round(p.lon * 1e6) / 1e6, std::round(p.lat * 1e6) / 1e6}; };
  std::map<LL, std::vector<std::pair<LL, double>>> adj;
  for (const auto& l : lines)
    for (size_t i = 1; i < l.size(); ++i) {
      const LL a = key(l[i - 1]), b = key(l[i]);
      adj[a].push_back({b, haversine(a, b)});
      adj[b].push_back({a, haversine(a, b)});
    }
  std::map<LL, double> dist;
  using Item = std::pair<double, LL>;
  auto cmp = [](const Item& a, const Item& b) { return a.first > b.first; };
  std::priority_queue<Item, std::vector<Item>, decltype(cmp)> q(cmp);
  q.push({0, key(from)});
  while (!q.empty()) {
    auto [d, v] = q.top();
    q.pop();
    if (dist.count(v)) continue;
    dist[v] = d;
    for (auto [w, m] : adj[v])
      if (!dist.count(w)) q.push({d + m, w});
  }
  return dist;
}

struct FeatureRow {
  std::string layer;
  tileformat::JsonValue props;
};

std::map<int64_t, FeatureRow> read_features(const std::string& pkg) {
  tileformat::PackageReader reader(pkg);
  tileformat::FeatureTableReader table(reader);
  std::map<int64_t, FeatureRow> out;
  table.for_each([&](int64_t id, const tileformat::FeatureRecord& r) {
    out[id] = {r.layer, tileformat::JsonValue::parse(r.properties)};
  });
  return out;
}

double num(const tileformat::JsonValue& o, const char* key) {
  const tileformat::JsonValue* v = o.find(key);
  return v && v->is_number() ? v->number() : NAN;
}

LL lonlat(const tileformat::JsonValue& o, const char* key) {
  const auto& a = o.find(key)->array();
  return {a[0].number(), a[1].number()};
}

class BundleCli : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  RunResult bundle(const std::string& args) {
    return run(vectorize() + " bundle " + args, dir_.path());
  }
  TempDir dir_;
};

struct Flow {
  LL from, to;
  double weight;
};

std::string flows_csv(const std::vector<Flow>& flows) {
  std::string s = "olon,olat,dlon,dlat,trips\n";
  for (const Flow& f : flows)
    s += fmt(f.from.lon) + "," + fmt(f.from.lat) + "," + fmt(f.to.lon) + "," + fmt(f.to.lat) + "," +
         std::to_string(int(f.weight)) + "\n";
  return s;
}

// Places a little off the grid's junctions and vertices.
std::vector<Flow> random_flows(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  auto place = [&] { return LL{10 + (rng() % 41) / 10.0 + 0.004, 45 + (rng() % 7) / 2.0 + 0.003}; };
  std::vector<Flow> out;
  while (int(out.size()) < n) {
    Flow f{place(), place(), double(1 + rng() % 50)};
    if (std::abs(f.from.lon - f.to.lon) + std::abs(f.from.lat - f.to.lat) > 0.2) out.push_back(f);
  }
  return out;
}

}  // namespace

// Routed lengths are shortest paths; each connection's bundles chain from
// its node to its destination's; bundle weights and counts are the sums of
// the connections listing them; at every node what the bundles bring equals
// what the paths take in and out.
TEST_F(BundleCli, RoutesAreShortestAndBundlesConserveWeight) {
  const auto lines = grid_lines();
  write_text(path("grid.geojson"), geojson_lines(lines));
  const auto flows = random_flows(80, 3);
  write_text(path("flows.csv"), flows_csv(flows));
  const RunResult r = bundle(path("flows.csv") + " --from olon,olat --to dlon,dlat --weight trips" +
                             " --network " + path("grid.geojson") + " -o " + path("b.mbtiles"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("80 routed, 0 unrouted"), std::string::npos) << r.err;
  const auto rows = read_features(path("b.mbtiles"));
  std::map<int64_t, const FeatureRow*> bundles;
  std::vector<const FeatureRow*> connections;
  for (const auto& [id, row] : rows) {
    if (row.layer == "bundles") bundles[id] = &row;
    if (row.layer == "connections") connections.push_back(&row);
  }
  ASSERT_EQ(connections.size(), flows.size());
  ASSERT_FALSE(bundles.empty());
  std::map<int64_t, double> weight, count;
  std::map<LL, double> at_node_by_paths, at_node_by_bundles;
  auto node_of = [](LL place) {  // the grid vertex a place snaps to
    return LL{std::round(place.lon * 10) / 10, std::round(place.lat * 10) / 10};
  };
  auto close = [](LL a, LL b) { return std::abs(a.lon - b.lon) + std::abs(a.lat - b.lat) < 1e-6; };
  for (size_t c = 0; c < connections.size(); ++c) {
    const auto& p = connections[c]->props;
    const Flow& f = flows[size_t(num(p, "row")) - 1];
    ASSERT_DOUBLE_EQ(num(p, "weight"), f.weight);
    LL at = node_of(f.from);
    for (const auto& b : p.find("bundles")->array()) {
      const int64_t id = int64_t(b.number());
      ASSERT_TRUE(bundles.count(id)) << "connection row " << c << ": no bundle " << id;
      weight[id] += f.weight;
      ++count[id];
      const LL from = lonlat(bundles[id]->props, "from"), to = lonlat(bundles[id]->props, "to");
      ASSERT_TRUE(close(from, at) || close(to, at))
          << "connection " << c << " breaks at bundle " << id;
      at_node_by_paths[node_of(at)] += f.weight;
      at = close(from, at) ? to : from;
      at_node_by_paths[node_of(at)] += f.weight;
    }
    EXPECT_TRUE(close(at, node_of(f.to))) << "connection " << c << " ends elsewhere";
    // The length: network shortest path plus the two snapping legs (1 %:
    // the tool measures on the ellipsoid, this test on a sphere).
    const double expected = network_distances(lines, node_of(f.from))[node_of(f.to)] +
                            haversine(f.from, node_of(f.from)) + haversine(f.to, node_of(f.to));
    EXPECT_NEAR(num(p, "length_m"), expected, 0.01 * expected) << "connection " << c;
  }
  for (const auto& [id, row] : bundles) {
    EXPECT_DOUBLE_EQ(num(row->props, "weight"), weight[id]) << "bundle " << id;
    EXPECT_DOUBLE_EQ(num(row->props, "count"), count[id]) << "bundle " << id;
    at_node_by_bundles[node_of(lonlat(row->props, "from"))] += weight[id];
    at_node_by_bundles[node_of(lonlat(row->props, "to"))] += weight[id];
  }
  EXPECT_EQ(at_node_by_bundles, at_node_by_paths);
  const RunResult v = run(vectorize() + " validate " + path("b.mbtiles"), dir_.path());
  EXPECT_EQ(v.exit_code, 0) << v.out;
  const RunResult info = run(vectorize() + " info " + path("b.mbtiles"), dir_.path());
  EXPECT_NE(info.out.find("connections 80: 80 routed, 0 unrouted"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("mean detour"), std::string::npos);
  EXPECT_NE(info.out.find("ink ratio"), std::string::npos);
}

// Drawn bundles (extract, read through OGR) stay within the corridor of the
// network at every zoom: 4 px, plus the tiles' quarter pixel of
// simplification and 1/16 px grid.
TEST_F(BundleCli, DrawnBundlesStayWithinTheCorridorOfTheNetwork) {
  const auto lines = grid_lines();
  write_text(path("grid.geojson"), geojson_lines(lines));
  write_text(path("flows.csv"), flows_csv(random_flows(40, 8)));
  const RunResult r =
      bundle(path("flows.csv") + " --from olon,olat --to dlon,dlat --network " +
             path("grid.geojson") + " --corridor-px 4 --max-zoom 9 -o " + path("b.mbtiles"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<Polyline> network;
  for (const auto& [id, parts] : read_lines(path("grid.geojson"), "", "", "EPSG:3857"))
    network.insert(network.end(), parts.begin(), parts.end());
  const auto rows = read_features(path("b.mbtiles"));
  for (int z : {2, 5, 7, 9}) {
    const std::string out = path("z" + std::to_string(z) + ".gpkg");
    ASSERT_EQ(run(vectorize() + " extract -q " + path("b.mbtiles") + " --zoom " +
                      std::to_string(z) + " -o " + out,
                  dir_.path())
                  .exit_code,
              0);
    const double px = 2 * std::numbers::pi * 6378137.0 / std::exp2(z) / 256;
    size_t drawn = 0;
    for (const auto& [id, parts] : read_lines(out, "lines", "feature_id")) {
      ASSERT_EQ(rows.at(id).layer, "bundles");
      EXPECT_LE(directed_hausdorff(parts, network), (4 + 0.25 + 0.1) * px)
          << "bundle " << id << " at zoom " << z;
      ++drawn;
    }
    EXPECT_GT(drawn, 0u) << "zoom " << z;
  }
}

// Ids joined to a CSV of locations (columns found by name) and to OGR
// points; bad rows (unknown ids, a missing weight) are counted, named and
// skipped; a place far from the network is drawn straight or dropped.
TEST_F(BundleCli, IdsLocationsBadRowsAndUnroutedConnections) {
  write_text(path("grid.geojson"), geojson_lines(grid_lines()));
  write_text(path("places.csv"),
             "code,name,latitude,longitude\nA,a,45.004,10.003\nB,b,48.002,14.001\n"
             "C,c,46.5,12.0\nFAR,far,30,30\n");
  write_text(path("trips.csv"),
             "src,dst,n\nA,B,10\nB,C,5\nA,C,\nA,NOPE,3\nC,FAR,2\nFAR,A,1\nA,B,0\n");
  const std::string common = path("trips.csv") + " --from-id src --to-id dst --weight n" +
                             " --id-field code --network " + path("grid.geojson");
  RunResult r = bundle(common + " --locations " + path("places.csv") + " -o " + path("s.mbtiles"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("4 connections from 7 rows (2 bad rows, 1 of weight 0): 2 routed, 2 "
                       "unrouted (2 beyond --max-snap"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("trips.csv row 3: weight (--weight 'n') missing"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("trips.csv row 4: id 'NOPE' is not in"), std::string::npos) << r.err;
  int straight = 0;
  for (const auto& [id, row] : read_features(path("s.mbtiles")))
    if (row.layer == "unrouted") ++straight;
  EXPECT_EQ(straight, 2);
  // The same places as GeoJSON points; unrouted connections dropped.
  std::string pts = "{\"type\":\"FeatureCollection\",\"features\":[";
  for (auto [code, lon, lat] : {std::tuple{"A", 10.003, 45.004},
                                {"B", 14.001, 48.002},
                                {"C", 12.0, 46.5},
                                {"FAR", 30.0, 30.0}})
    pts += std::string(code[0] == 'A' ? "" : ",") +
           "{\"type\":\"Feature\",\"properties\":" + "{\"code\":\"" + code +
           "\"},\"geometry\":{\"type\":\"Point\",\"coordinates\":[" + fmt(lon) + "," + fmt(lat) +
           "]}}";
  write_text(path("places.geojson"), pts + "]}");
  r = bundle(common + " --locations " + path("places.geojson") + " --unrouted drop -o " +
             path("d.mbtiles"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int connections = 0;
  for (const auto& [id, row] : read_features(path("d.mbtiles"))) {
    EXPECT_NE(row.layer, "unrouted");
    if (row.layer == "connections") ++connections;
  }
  EXPECT_EQ(connections, 4);  // dropped from the drawing, not from the table
}

// --label-field: one label per end of the connections at its location, named
// by the locations' column (the id where it is empty), ranked by the weight
// through it (here summed by hand from trips.csv), usable rows only.
TEST_F(BundleCli, EndsAreLabelledByTheirLocationsName) {
  write_text(path("grid.geojson"), geojson_lines(grid_lines()));
  write_text(path("places.csv"),
             "code,name,latitude,longitude\nA,Alpha,45.004,10.003\nB,,48.002,14.001\n"
             "C,Gamma,46.5,12.0\nD,Delta,47,13\n");
  write_text(path("trips.csv"), "src,dst,n\nA,B,10\nB,C,5\nA,C,2\n");
  const std::string common = path("trips.csv") + " --from-id src --to-id dst --weight n" +
                             " --id-field code --network " + path("grid.geojson") +
                             " --locations " + path("places.csv");
  RunResult r = bundle(common + " --label-field name -o " + path("l.mbtiles"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const RunResult rows =
      run("sqlite3 " + path("l.mbtiles") +
              " 'SELECT text, priority, lon, lat, placement FROM labels ORDER BY id'",
          path(""));
  EXPECT_EQ(rows.out,
            "Alpha|12.0|10.003|45.004|0\nB|15.0|14.001|48.002|0\nGamma|7.0|12.0|46.5|0\n");
  // Without --locations there is nothing to name the ends by.
  r = bundle(path("trips.csv") + " --from-id src --to-id dst --label-field name -o " +
             path("x.mbtiles"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
}

// A network split at the antimeridian (as GeoJSON asks) is one network: the
// connection goes 18 degrees west, not 342 east, and its bundle is drawn on
// both sides without a segment across the world.
TEST_F(BundleCli, TheAntimeridianJoinsTheNetwork) {
  write_text(path("pacific.geojson"),
             geojson_lines({{{170, 0}, {172, 0}, {174, 0}, {176, 0}, {178, 0}, {180, 0}},
                            {{-180, 0}, {-178, 0}, {-176, 0}, {-174, 0}, {-172, 0}, {-170, 0}}}));
  write_text(path("flows.csv"), flows_csv({{{172.1, 0.05}, {-172.1, 0.05}, 4}}));
  const RunResult r = bundle(path("flows.csv") + " --from olon,olat --to dlon,dlat --network " +
                             path("pacific.geojson") + " -o " + path("p.mbtiles"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("1 routed"), std::string::npos) << r.err;
  for (const auto& [id, row] : read_features(path("p.mbtiles")))
    if (row.layer == "connections") {
      // 172 E to 172 W over the network, plus two legs of 12 km to it.
      EXPECT_NEAR(num(row.props, "length_m"), 16 * 111320.0 + 2 * 12300, 5000);
    }
  ASSERT_EQ(run(vectorize() + " extract -q " + path("p.mbtiles") + " --zoom 3 -o " + path("z.gpkg"),
                dir_.path())
                .exit_code,
            0);
  double west = 0, east = 0;
  for (const auto& [id, parts] : read_lines(path("z.gpkg"), "lines", "feature_id"))
    for (const Polyline& l : parts)
      for (size_t i = 0; i < l.size(); ++i) {
        west = std::min(west, l[i].x);
        east = std::max(east, l[i].x);
        if (i) {
          EXPECT_LT(std::abs(l[i].x - l[i - 1].x), 3e6) << "a segment across the world";
        }
      }
  EXPECT_LT(west, -1.8e7);
  EXPECT_GT(east, 1.8e7);
}

TEST_F(BundleCli, SameBytesForAnyThreadCount) {
  write_text(path("grid.geojson"), geojson_lines(grid_lines()));
  write_text(path("flows.csv"), flows_csv(random_flows(60, 5)));
  const std::string args = path("flows.csv") + " --from olon,olat --to dlon,dlat --weight trips" +
                           " --network " + path("grid.geojson");
  fs::create_directories(dir_ / "one");
  fs::create_directories(dir_ / "three");
  ASSERT_EQ(
      run("cd " + path("one") + " && " + vectorize() + " bundle " + args + " -j1 -o b.mbtiles",
          dir_.path())
          .exit_code,
      0);
  ASSERT_EQ(
      run("cd " + path("three") + " && " + vectorize() + " bundle " + args + " -j3 -o b.mbtiles",
          dir_.path())
          .exit_code,
      0);
  const bool same = read_file(path("one/b.mbtiles")) == read_file(path("three/b.mbtiles"));
  EXPECT_TRUE(same) << "-j1 and -j3 packages differ";
}

TEST_F(BundleCli, BadInputSaysWhatIsWrongAndWritesNothing) {
  write_text(path("grid.geojson"), geojson_lines(grid_lines()));
  write_text(path("flows.csv"), flows_csv(random_flows(5, 1)));
  write_text(path("empty.csv"), "olon,olat,dlon,dlat,trips\n");
  // The same flows on the other side of the Atlantic.
  std::vector<Flow> far = random_flows(5, 1);
  for (Flow& f : far)
    f.from.lon -= 90, f.to.lon -= 90;
  write_text(path("far.csv"), flows_csv(far));
  write_text(path("points.geojson"),
             "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":"
             "{},\"geometry\":{\"type\":\"Point\",\"coordinates\":[10,45]}}]}");
  const std::string xy = " --from olon,olat --to dlon,dlat --network ";
  auto expect_error = [&](const std::string& args, int code, const std::string& says) {
    const RunResult r = bundle(args + " -o " + path("out.mbtiles"));
    EXPECT_EQ(r.exit_code, code) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << args << "\n" << r.err;
    EXPECT_FALSE(fs::exists(path("out.mbtiles"))) << args;
    EXPECT_FALSE(fs::exists(path("out.mbtiles.tmp"))) << args;
  };
  const std::string grid = path("grid.geojson");
  expect_error(path("far.csv") + xy + grid, 1,
               "none of its 10 places lies within --max-snap 25000 m of a node of the network");
  expect_error(path("empty.csv") + xy + grid, 1, "empty.csv: no usable connection in 0 rows");
  expect_error(path("flows.csv") + " --from olon,nope --to dlon,dlat --network " + grid, 2,
               "--from 'nope': " + path("flows.csv") + " layer 'flows' has no such field");
  expect_error(path("flows.csv") + xy + grid + " --weight count", 2, "--weight 'count'");
  expect_error(path("flows.csv") + xy + path("points.geojson"), 1,
               "holds points; a network is lines");
  expect_error(path("flows.csv") + " --from olon,olat --to dlon,dlat", 2, "--network is required");
  expect_error(path("flows.csv") + " --from-id a --to-id b --network " + grid, 2,
               "add --locations FILE --id-field COL");
  expect_error(path("flows.csv") + " --network " + grid, 2, "say where connections start and end");
  expect_error(path("flows.csv") + xy + grid + " --unrouted maybe", 2,
               "--unrouted: 'maybe' is not straight or drop");
  expect_error(path("flows.csv") + xy + grid + " --significance 2", 2,
               "--significance: expected a share from 0 to 1");
  expect_error(path("flows.csv") + xy + grid + " --opacities 0.5,0.2", 2,
               "--opacities: expected 0 < MIN <= MAX <= 1");
  expect_error(path("flows.csv") + xy + grid + " --min-weight -1", 2,
               "--min-weight must be 0 or more");
  expect_error(path("flows.csv") + xy + grid + " --style weight-1:opacity=3", 2,
               "opacity '3' is not between 0 and 1");
}

// The significance filter and --min-weight as the summary and info count
// them: by default the coarsest zoom hides the light flows of the grid,
// with --significance 0 none; --min-weight above every weight draws nothing
// and says so.
TEST_F(BundleCli, SignificanceAndMinWeightAreCountedAndReported) {
  write_text(path("grid.geojson"), geojson_lines(grid_lines()));
  std::vector<Flow> flows = random_flows(60, 7);
  flows[0].weight = 100000;  // one trunk flow far heavier than the rest
  write_text(path("flows.csv"), flows_csv(flows));
  const std::string args = path("flows.csv") + " --from olon,olat --to dlon,dlat --weight trips " +
                           "--network " + path("grid.geojson") + " --tiling geodetic -o ";
  auto hidden = [&](const std::string& name, const std::string& extra) {
    const RunResult r = bundle(args + path(name) + extra);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const RunResult info = run(vectorize() + " info " + path(name), dir_.path());
    EXPECT_EQ(info.exit_code, 0) << info.err;
    unsigned long long n = 0, never = 0;
    const size_t at = info.out.find("  significance ");
    EXPECT_NE(at, std::string::npos) << info.out;
    if (at != std::string::npos) {
      EXPECT_EQ(std::sscanf(info.out.c_str() + at,
                            "  significance %*g of the heaviest flow in view: %llu flows hidden "
                            "at the coarsest zoom; --min-weight %*g: %llu never drawn",
                            &n, &never),
                2)
          << info.out;
    }
    return std::pair(n, never);
  };
  const auto [by_default, none_never] = hidden("default.mbtiles", "");
  EXPECT_GT(by_default, 0u);
  EXPECT_EQ(none_never, 0u);
  EXPECT_EQ(hidden("all.mbtiles", " --significance 0").first, 0u);
  const RunResult r = bundle(args + path("none.mbtiles") + " --min-weight 1000000");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("every bundle and line is lighter than --min-weight 1000000 (the "
                       "heaviest weighs "),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(path("none.mbtiles")));
}
