// `globe-vectorize bundle` on real global flows (issue 33): airports world-wide
// (samples/data/world_airports.csv, FlightGear's ILS airports) joined in pairs
// weighted by their runway ends, over FlightGear's world-wide airway network
// (samples/data/airways.geojson), with the transoceanic and antimeridian
// routes that once never came back from the path reconstruction. Every row
// ends routed or unrouted with a reason, and each routed length equals a
// shortest path computed here: the airways read through OGR, nodes joined by
// their coordinates, haversine lengths, Dijkstra, the nearest node by brute
// force; sharing nothing with the tool.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <queue>
#include <random>
#include <sstream>

#include "line_fixtures.hpp"
#include "test_support.hpp"
#include "tileformat/feature_table.hpp"
#include "tileformat/json.hpp"
#include "tileformat/package.hpp"

using namespace globe_test;

namespace {

struct LL {
  double lon, lat;
};

double haversine(LL a, LL b) {
  return haversine_m(a.lon, a.lat, b.lon, b.lat);
}

// The airway network as a graph: a node per distinct coordinate (to 1e-6
// degrees; -180 and 180 are one), an edge per segment.
struct Airways {
  std::vector<LL> nodes;
  std::vector<std::vector<std::pair<uint32_t, double>>> adj;

  explicit Airways(const std::string& geojson) {
    std::map<std::pair<int64_t, int64_t>, uint32_t> id;
    auto node = [&](globe::XY p) {
      int64_t x = std::llround(p.x * 1e6), y = std::llround(p.y * 1e6);
      if (x == 180000000) x = -180000000;
      auto [it, fresh] = id.try_emplace({x, y}, uint32_t(nodes.size()));
      if (fresh) nodes.push_back({p.x, p.y}), adj.emplace_back();
      return it->second;
    };
    for (const auto& [fid, parts] : read_lines(geojson, "", ""))
      for (const Polyline& l : parts)
        for (size_t i = 1; i < l.size(); ++i) {
          const uint32_t a = node(l[i - 1]), b = node(l[i]);
          if (a == b) continue;
          const double m = haversine(nodes[a], nodes[b]);
          adj[a].push_back({b, m});
          adj[b].push_back({a, m});
        }
  }

  // The nearest node and its distance (brute force).
  std::pair<uint32_t, double> nearest(LL p) const {
    std::pair<uint32_t, double> best{0, INFINITY};
    for (uint32_t i = 0; i < nodes.size(); ++i)
      if (const double m = haversine(p, nodes[i]); m < best.second) best = {i, m};
    return best;
  }

  std::vector<double> distances(uint32_t from) const {
    std::vector<double> d(nodes.size(), INFINITY);
    using Item = std::pair<double, uint32_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> q;
    d[from] = 0;
    q.push({0, from});
    while (!q.empty()) {
      auto [c, v] = q.top();
      q.pop();
      if (c > d[v]) continue;
      for (auto [w, m] : adj[v])
        if (c + m < d[w]) d[w] = c + m, q.push({c + m, w});
    }
    return d;
  }
};

struct Airport {
  std::string icao;
  LL at;
  int runway_ends;
};

std::vector<Airport> read_airports(const std::string& csv) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);  // icao,lon,lat,ils_runway_ends
  std::vector<Airport> out;
  while (std::getline(in, line)) {
    std::stringstream s(line);
    std::string icao, lon, lat, n;
    std::getline(s, icao, ','), std::getline(s, lon, ','), std::getline(s, lat, ',');
    std::getline(s, n, ',');
    out.push_back({icao, {std::stod(lon), std::stod(lat)}, std::stoi(n)});
  }
  return out;
}

class GlobalFlights : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  TempDir dir_;
};

}  // namespace

// Origin-destination pairs between the world's ILS airports: a fixed list of
// transoceanic and antimeridian routes (London -> Los Angeles and Frankfurt ->
// Las Vegas crashed the tool), then random pairs drawn with probability
// proportional to runway ends. Every row is routed or unrouted with a
// reason; each routed length is the shortest path over the airways.
TEST_F(GlobalFlights, TransoceanicAndAntimeridianRoutesAreShortestPaths) {
  const auto airports = read_airports(sample("world_airports.csv").string());
  ASSERT_GT(airports.size(), 2000u);
  std::map<std::string, size_t> by_icao;
  for (size_t i = 0; i < airports.size(); ++i)
    by_icao[airports[i].icao] = i;
  std::vector<std::pair<size_t, size_t>> pairs;
  for (auto [a, b] : std::vector<std::pair<const char*, const char*>>{
           {"EGLL", "KLAX"},  // London -> Los Angeles
           {"EDDF", "KLAS"},  // Frankfurt -> Las Vegas
           {"EDDF", "KJFK"},
           {"KSFO", "RJAA"},  // San Francisco -> Tokyo, across the antimeridian
           {"RJAA", "KSFO"},
           {"EDDF", "OMDB"},
           {"PHNL", "NZAA"},  // Honolulu -> Auckland, across it southwards
           {"YSSY", "KLAX"},  // Sydney -> Los Angeles
           {"SBGR", "FAJS"},  // Sao Paulo -> Johannesburg
           {"PANC", "RKSI"},  // Anchorage -> Seoul
           {"EGLL", "YSSY"}}) {
    ASSERT_TRUE(by_icao.count(a) && by_icao.count(b)) << a << " or " << b;
    pairs.push_back({by_icao[a], by_icao[b]});
  }
  std::vector<double> runway_ends;
  for (const Airport& a : airports)
    runway_ends.push_back(a.runway_ends);
  std::mt19937 rng(33);
  std::discrete_distribution<size_t> pick(runway_ends.begin(), runway_ends.end());
  while (pairs.size() < 600) {
    const size_t a = pick(rng), b = pick(rng);
    if (a != b) pairs.push_back({a, b});
  }
  std::string csv = "origin,olon,olat,destination,dlon,dlat,weight\n";
  for (auto [a, b] : pairs) {
    const Airport &o = airports[a], &d = airports[b];
    char row[200];
    std::snprintf(row, sizeof row, "%s,%.6f,%.6f,%s,%.6f,%.6f,%d\n", o.icao.c_str(), o.at.lon,
                  o.at.lat, d.icao.c_str(), d.at.lon, d.at.lat, o.runway_ends + d.runway_ends);
    csv += row;
  }
  write_text(path("flows.csv"), csv);

  const std::string airways_file = sample("airways.geojson").string();
  const RunResult r =
      run(vectorize() + " bundle " + path("flows.csv") +
              " --from olon,olat --to dlon,dlat --weight weight --max-zoom 6 --network " +
              airways_file + " -o " + path("world.mbtiles"),
          dir_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;

  // The reference, with --max-snap's default 25 km.
  const Airways net(airways_file);
  ASSERT_GT(net.nodes.size(), 20000u);
  constexpr double kMaxSnapM = 25000;
  // Checked against it: the listed routes and the first random ones.
  constexpr size_t kChecked = 120;
  std::map<size_t, std::pair<uint32_t, double>> snap;
  for (size_t i = 0; i < kChecked; ++i)
    for (size_t p : {pairs[i].first, pairs[i].second})
      if (!snap.count(p)) snap[p] = net.nearest(airports[p].at);
  std::map<uint32_t, std::vector<double>> from_node;

  tileformat::PackageReader reader(path("world.mbtiles"));
  tileformat::FeatureTableReader table(reader);
  size_t rows = 0, routed = 0, checked = 0, antimeridian = 0;
  table.for_each([&](int64_t, const tileformat::FeatureRecord& rec) {
    if (rec.layer != "connections") return;
    ++rows;
    const auto props = tileformat::JsonValue::parse(rec.properties);
    const size_t row = size_t(props.find("row")->number());
    ASSERT_GE(row, 1u);
    ASSERT_LE(row, pairs.size());
    const auto [a, b] = pairs[row - 1];
    const auto* length = props.find("length_m");
    routed += length != nullptr;
    if (row > kChecked) {
      EXPECT_TRUE(length || !props.find("unrouted")->string().empty()) << rec.properties;
      return;
    }
    const auto [na, ma] = snap[a];
    const auto [nb, mb] = snap[b];
    if (!length) {
      EXPECT_GT(row, 11u) << airports[a].icao << " -> " << airports[b].icao
                          << " (a listed route) is unrouted: " << rec.properties;
      ASSERT_NE(props.find("unrouted"), nullptr) << rec.properties;
      EXPECT_FALSE(props.find("unrouted")->string().empty()) << rec.properties;
      // Unrouted only where the reference cannot route it either (the
      // ellipsoid and the sphere may disagree within 0.6 % of 25 km).
      if (ma < 0.99 * kMaxSnapM && mb < 0.99 * kMaxSnapM && na != nb) {
        if (!from_node.count(na)) from_node[na] = net.distances(na);
        EXPECT_FALSE(std::isfinite(from_node[na][nb]))
            << "row " << row << " " << airports[a].icao << " -> " << airports[b].icao << ": "
            << rec.properties;
      }
      return;
    }
    if (ma > 0.99 * kMaxSnapM || mb > 0.99 * kMaxSnapM) return;  // at the snapping limit
    if (!from_node.count(na)) from_node[na] = net.distances(na);
    const double expected = from_node[na][nb] + ma + mb;
    ASSERT_TRUE(std::isfinite(expected)) << "row " << row << ": routed, but not connected here";
    // 1 %: the tool measures on the ellipsoid, this test on a sphere.
    EXPECT_NEAR(length->number(), expected, 0.01 * expected + 100)
        << "row " << row << " " << airports[a].icao << " -> " << airports[b].icao;
    ++checked;
    const double west = std::min(airports[a].at.lon, airports[b].at.lon);
    const double east = std::max(airports[a].at.lon, airports[b].at.lon);
    if (row <= 11 && east - west > 180) ++antimeridian;
  });
  EXPECT_EQ(rows, pairs.size());
  EXPECT_GE(checked, kChecked * 7 / 10);
  EXPECT_GE(antimeridian, 4u);  // SFO-NRT both ways, HNL-AKL, SYD-LAX, ANC-ICN
  // The listed routes are all routed; most random pairs too.
  EXPECT_GT(routed, pairs.size() * 8 / 10) << r.err;
  EXPECT_NE(r.err.find(std::to_string(routed) + " routed"), std::string::npos) << r.err;
  const RunResult v = run(vectorize() + " validate " + path("world.mbtiles"), dir_.path());
  EXPECT_EQ(v.exit_code, 0) << v.out << v.err;
}
