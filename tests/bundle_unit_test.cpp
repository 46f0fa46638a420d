// The stages of a bundling (docs/bundles.md) on small and random graphs:
// routes are shortest paths (against a reference Dijkstra written here on
// the full, unreduced graph), connected chains from origin to destination, the
// same for any thread count; the graph reduction keeps every distance;
// bundles partition the used edges, carry the sums of their connections and
// conserve weight at every node; smoothed curves stay within their corridor
// (distances measured here to the whole polyline), keep their ends, and
// coarser zooms use fewer points.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>

#include "bundle/bundle_curve.hpp"
#include "bundle/bundles.hpp"
#include "bundle/network_graph.hpp"
#include "bundle/routing.hpp"
#include "bundle/significance.hpp"
#include "geo/geodesic.hpp"
#include "kit/progress.hpp"
#include "test_support.hpp"

namespace globe {
namespace {

// A random planar-ish road graph: n nodes scattered over a few degrees,
// each joined to a few near neighbours by lines of 1 to 4 segments (so the
// reduction has chains to collapse).
struct RandomNetwork {
  std::vector<std::vector<LonLat>> lines;
  std::vector<LonLat> places;
};

RandomNetwork random_network(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> lon(10, 14), lat(45, 48), jitter(-0.02, 0.02);
  RandomNetwork net;
  for (int i = 0; i < n; ++i)
    net.places.push_back({lon(rng), lat(rng)});
  for (int i = 0; i < n; ++i) {
    std::vector<std::pair<double, int>> near;
    for (int j = 0; j < n; ++j)
      if (j != i)
        near.push_back({std::hypot(net.places[i].lon - net.places[j].lon,
                                   net.places[i].lat - net.places[j].lat),
                        j});
    std::sort(near.begin(), near.end());
    for (int k = 0; k < 3; ++k) {
      const LonLat a = net.places[size_t(i)], b = net.places[size_t(near[size_t(k)].second)];
      std::vector<LonLat> line{a};
      const int segments = 1 + int(rng() % 4);
      for (int s = 1; s < segments; ++s) {
        const double t = double(s) / segments;
        line.push_back(
            {a.lon + t * (b.lon - a.lon) + jitter(rng), a.lat + t * (b.lat - a.lat) + jitter(rng)});
      }
      line.push_back(b);
      net.lines.push_back(line);
    }
  }
  return net;
}

NetworkGraph build_graph(const std::vector<std::vector<LonLat>>& lines) {
  NetworkGraph::Builder b(1.0);
  for (const auto& l : lines)
    b.add_line({l}, std::nan(""));
  return b.finish();
}

// Reference: Dijkstra over the unreduced graph, O(n^2) with arrays, costs
// recomputed here from the nodes (geodesic length of each edge).
std::vector<double> reference_distances(const NetworkGraph& g, uint32_t from) {
  const size_t n = g.nodes().size();
  std::vector<std::vector<std::pair<uint32_t, double>>> adj(n);
  for (const auto& e : g.edges()) {
    const LonLat a = g.nodes()[e.a], b = g.nodes()[e.b];
    const double m = geodesic_distance_m(a.lon, a.lat, b.lon, b.lat);
    adj[e.a].push_back({e.b, m});
    adj[e.b].push_back({e.a, m});
  }
  std::vector<double> d(n, std::numeric_limits<double>::infinity());
  std::vector<char> done(n, 0);
  d[from] = 0;
  for (size_t round = 0; round < n; ++round) {
    size_t v = n;
    for (size_t i = 0; i < n; ++i)
      if (!done[i] && std::isfinite(d[i]) && (v == n || d[i] < d[v])) v = i;
    if (v == n) break;
    done[v] = 1;
    for (auto [w, m] : adj[v])
      d[w] = std::min(d[w], d[v] + m);
  }
  return d;
}

struct Routed {
  NetworkGraph graph;
  ReducedGraph reduced;
  std::vector<uint32_t> place_node;  // graph node of each place
  std::vector<OriginDestination> od;
  std::vector<std::pair<uint32_t, uint32_t>> od_places;
};

Routed route_random(const RandomNetwork& net, int connections, uint32_t seed) {
  Routed r{build_graph(net.lines), {}, {}, {}, {}};
  std::vector<char> terminal(r.graph.nodes().size(), 0);
  for (const LonLat& p : net.places) {
    const auto n = r.graph.nearest(p, 1.0);
    EXPECT_TRUE(n.has_value());
    r.place_node.push_back(*n);
    terminal[*n] = 1;
  }
  r.reduced = reduce_graph(r.graph, terminal);
  std::mt19937 rng(seed);
  for (int c = 0; c < connections; ++c) {
    const uint32_t a = rng() % net.places.size(), b = rng() % net.places.size();
    if (a == b || r.graph.component(r.place_node[a]) != r.graph.component(r.place_node[b]))
      continue;
    r.od_places.push_back({a, b});
    r.od.push_back({uint32_t(r.reduced.reduced_node[r.place_node[a]]),
                    uint32_t(r.reduced.reduced_node[r.place_node[b]])});
  }
  return r;
}

// Loops hung on every `every`-th place: a triangle out of the place and back
// (a lasso: one reduced edge from the place to itself), and beside it a ring
// of three nodes touching nothing (an interior loop, no junction).
void add_loops(RandomNetwork& net, size_t every) {
  for (size_t i = 0; i < net.places.size(); i += every) {
    const LonLat p = net.places[i];
    net.lines.push_back({p, {p.lon + 0.03, p.lat + 0.005}, {p.lon + 0.02, p.lat + 0.03}, p});
    const LonLat q{p.lon - 0.05, p.lat - 0.05};
    net.lines.push_back({q, {q.lon + 0.01, q.lat}, {q.lon, q.lat + 0.01}, q});
  }
}

// Every reduced node lists exactly the edges that touch it: a loop once,
// any other edge once at each end.
void expect_consistent_adjacency(const ReducedGraph& r) {
  std::vector<uint32_t> listed(r.edges.size(), 0);
  for (uint32_t v = 0; v + 1 < r.offsets.size(); ++v)
    for (uint32_t k = r.offsets[v]; k < r.offsets[v + 1]; ++k) {
      const ReducedGraph::Edge& e = r.edges[r.incident[k]];
      EXPECT_TRUE(e.a == v || e.b == v) << "node " << v << " lists edge " << r.incident[k];
      ++listed[r.incident[k]];
    }
  for (uint32_t e = 0; e < r.edges.size(); ++e)
    EXPECT_EQ(listed[e], r.edges[e].a == r.edges[e].b ? 1u : 2u) << "edge " << e;
}

void expect_shortest_chains(uint32_t seed, bool loops) {
  Progress quiet(ProgressMode::kQuiet);
  {
    RandomNetwork net = random_network(60, seed);
    if (loops) add_loops(net, 3);
    const Routed r = route_random(net, 150, seed * 7);
    ASSERT_GT(r.od.size(), 50u);
    expect_consistent_adjacency(r.reduced);
    std::map<uint32_t, std::vector<double>> reference;
    const auto routes = route_connections(r.reduced, r.od, 2, quiet);
    for (size_t c = 0; c < r.od.size(); ++c) {
      const uint32_t from = r.place_node[r.od_places[c].first];
      const uint32_t to = r.place_node[r.od_places[c].second];
      if (!reference.count(from)) reference[from] = reference_distances(r.graph, from);
      ASSERT_FALSE(routes[c].empty()) << "seed " << seed << " connection " << c;
      // A chain of reduced edges from origin to destination...
      uint32_t at = r.od[c].origin;
      double cost = 0;
      for (uint32_t e : routes[c]) {
        const ReducedGraph::Edge& edge = r.reduced.edges[e];
        ASSERT_TRUE(edge.a == at || edge.b == at) << "seed " << seed << ": route breaks";
        at = edge.a == at ? edge.b : edge.a;
        // ... whose graph nodes are consecutive graph edges.
        for (uint32_t k = edge.first; k + 1 < edge.first + edge.count; ++k) {
          const LonLat p = r.graph.nodes()[r.reduced.path[k]];
          const LonLat q = r.graph.nodes()[r.reduced.path[k + 1]];
          cost += geodesic_distance_m(p.lon, p.lat, q.lon, q.lat);
        }
      }
      EXPECT_EQ(at, r.od[c].destination);
      // ... as short as the reference's (1 mm per km of rounding).
      EXPECT_NEAR(cost, reference[from][to], 1e-6 * reference[from][to] + 1e-3)
          << "seed " << seed << " connection " << c;
    }
  }
}

TEST(BundleRouting, ShortestPathsMatchAReferenceDijkstraAndAreConnectedChains) {
  for (uint32_t seed : {1u, 2u, 3u})
    expect_shortest_chains(seed, false);
}

// Loops in the network (a lasso reduces to an edge from a node to itself)
// once left a slot of their node's adjacency unfilled, read as edge 0: the
// route back from a destination then never reached its origin (issue 33:
// bad_alloc on London -> Los Angeles over the airways).
TEST(BundleRouting, LoopsInTheNetworkKeepRoutesShortestChains) {
  for (uint32_t seed : {4u, 5u, 6u})
    expect_shortest_chains(seed, true);
}

TEST(BundleRouting, RoutesDoNotDependOnTheThreadCount) {
  Progress quiet(ProgressMode::kQuiet);
  const RandomNetwork net = random_network(80, 11);
  const Routed r = route_random(net, 300, 5);
  const auto one = route_connections(r.reduced, r.od, 1, quiet);
  for (int threads : {2, 3, 8})
    EXPECT_EQ(route_connections(r.reduced, r.od, threads, quiet), one) << threads << " threads";
}

TEST(BundleGraph, ReductionCollapsesChainsAndKeepsTerminalsAndLengths) {
  // A line of 5 segments between two junctions, a terminal in its middle.
  const std::vector<std::vector<LonLat>> lines = {
      {{0, 0}, {0.1, 0}, {0.2, 0}, {0.3, 0}, {0.4, 0}, {0.5, 0}},
      {{0, 0}, {0, 0.1}},
      {{0, 0}, {0, -0.1}},  // a junction at (0, 0)
      {{0.5, 0}, {0.5, 0.1}},
      {{0.5, 0}, {0.5, -0.1}}  // and at (0.5, 0)
  };
  const NetworkGraph g = build_graph(lines);
  EXPECT_EQ(g.nodes().size(), 10u);
  EXPECT_EQ(g.edges().size(), 9u);
  EXPECT_EQ(g.stats().components, 1u);
  std::vector<char> terminal(g.nodes().size(), 0);
  terminal[*g.nearest({0.3, 0}, 1)] = 1;
  const ReducedGraph r = reduce_graph(g, terminal);
  // Kept: 2 junctions, 4 dead ends, the terminal; the long line is 2 edges.
  EXPECT_EQ(r.graph_node.size(), 7u);
  EXPECT_EQ(r.edges.size(), 6u);
  double total = 0, reduced_total = 0;
  for (const auto& e : g.edges())
    total += e.length_m;
  for (const auto& e : r.edges)
    reduced_total += e.length_m;
  EXPECT_NEAR(reduced_total, total, 1e-6);
  // Parallel lines keep the cheaper; a far-away second piece is a component.
  const NetworkGraph h = build_graph({{{0, 0}, {1, 0}}, {{0, 0}, {1, 0}}, {{5, 5}, {5, 6}}});
  EXPECT_EQ(h.edges().size(), 2u);
  EXPECT_EQ(h.stats().parallel, 1u);
  EXPECT_EQ(h.stats().components, 2u);
  EXPECT_FALSE(h.nearest({3, 3}, 1000).has_value());
  EXPECT_TRUE(h.nearest({3, 3}, 500000).has_value());
}

TEST(BundleGraph, NearestNodeWrapsAtTheAntimeridian) {
  const NetworkGraph g = build_graph({{{179.99, 10}, {179.5, 10}}, {{-179.0, 10}, {-178, 10}}});
  const auto n = g.nearest({-179.995, 10}, 5000);
  ASSERT_TRUE(n.has_value());
  EXPECT_DOUBLE_EQ(g.nodes()[*n].lon, 179.99);  // 1.6 km west across the antimeridian
}

// Unrouted connections are drawn along the geodesic: London -> Los Angeles
// in steps of 10 km (or a little less) goes far north, over Hudson Bay, and
// its steps add up to the great circle within the sphere's 0.6 %. (The
// line's length was once NaN, and the curve one straight step.)
TEST(BundleGeodesic, StraightLinesFollowTheGeodesic) {
  const auto pts = geodesic_points(-0.4619, 51.4706, -118.4081, 33.9425, 10000);
  ASSERT_GT(pts.size(), 870u);
  ASSERT_LT(pts.size(), 890u);
  double north = -90, total = 0;
  for (size_t i = 1; i < pts.size(); ++i) {
    north = std::max(north, pts[i].second);
    const double h =
        globe_test::haversine_m(pts[i - 1].first, pts[i - 1].second, pts[i].first, pts[i].second);
    EXPECT_NEAR(h, 10000, 150) << "step " << i;
    total += h;
  }
  EXPECT_GT(north, 60);
  EXPECT_NEAR(total,
              globe_test::haversine_m(pts.front().first, pts.front().second, pts.back().first,
                                      pts.back().second),
              0.006 * total);
  EXPECT_DOUBLE_EQ(pts.back().first, -118.4081);
}

TEST(BundleSets, BundlesPartitionTheUsedEdgesAndConserveWeightAtEveryNode) {
  Progress quiet(ProgressMode::kQuiet);
  const RandomNetwork net = random_network(70, 21);
  const Routed r = route_random(net, 400, 9);
  const auto routes = route_connections(r.reduced, r.od, 2, quiet);
  std::vector<double> weights;
  std::mt19937 rng(4);
  for (size_t c = 0; c < routes.size(); ++c)
    weights.push_back(1 + rng() % 100);
  const BundleSet set = make_bundles(r.reduced, routes, weights);
  ASSERT_EQ(set.paths.size(), routes.size());
  // Each bundle's weight and count are the sums over the connections
  // listing it; a connection's bundles form a chain from origin to
  // destination node; no two consecutive bundles of one connection match.
  std::vector<double> weight(set.bundles.size(), 0);
  std::vector<uint32_t> count(set.bundles.size(), 0);
  std::map<uint32_t, double> node_from_bundles, node_from_connections;
  for (size_t c = 0; c < routes.size(); ++c) {
    uint32_t at = r.reduced.graph_node[r.od[c].origin];
    for (uint32_t b : set.paths[c]) {
      weight[b] += weights[c];
      ++count[b];
      const Bundle& bundle = set.bundles[b];
      ASSERT_TRUE(bundle.nodes.front() == at || bundle.nodes.back() == at)
          << "connection " << c << ": bundle " << b << " does not continue its path";
      node_from_connections[at] += weights[c];
      at = bundle.nodes.front() == at ? bundle.nodes.back() : bundle.nodes.front();
      node_from_connections[at] += weights[c];
    }
    EXPECT_EQ(at, r.reduced.graph_node[r.od[c].destination]);
  }
  for (size_t b = 0; b < set.bundles.size(); ++b) {
    EXPECT_DOUBLE_EQ(set.bundles[b].weight, weight[b]) << "bundle " << b;
    EXPECT_EQ(set.bundles[b].count, count[b]) << "bundle " << b;
    node_from_bundles[set.bundles[b].nodes.front()] += set.bundles[b].weight;
    node_from_bundles[set.bundles[b].nodes.back()] += set.bundles[b].weight;
  }
  // In = out at every node: what the bundles bring equals what the paths
  // through it take in and out (origins and destinations once).
  EXPECT_EQ(node_from_bundles, node_from_connections);
  // Maximal: where exactly two bundles meet, they carry different sets.
  std::map<uint32_t, std::vector<uint32_t>> at_node;
  for (uint32_t b = 0; b < set.bundles.size(); ++b) {
    at_node[set.bundles[b].nodes.front()].push_back(b);
    at_node[set.bundles[b].nodes.back()].push_back(b);
  }
  std::vector<std::set<size_t>> members(set.bundles.size());
  for (size_t c = 0; c < routes.size(); ++c)
    for (uint32_t b : set.paths[c])
      members[b].insert(c);
  for (const auto& [node, bs] : at_node)
    for (size_t i = 0; i < bs.size(); ++i)
      for (size_t j = i + 1; j < bs.size(); ++j)
        if (bs[i] != bs[j]) {
          EXPECT_NE(members[bs[i]], members[bs[j]]) << "node " << node;
        }
}

TEST(BundleSets, ConnectionsSharingACorridorShareOneBundle) {
  // A - X - Y - B with C and D joining at X and Y: A->B and C->D share X-Y.
  const std::vector<std::vector<LonLat>> lines = {{{0, 0}, {1, 0}},
                                                  {{1, 0}, {1.5, 0.01}, {2, 0}},
                                                  {{2, 0}, {3, 0}},
                                                  {{1, 1}, {1, 0}},
                                                  {{2, -1}, {2, 0}}};
  const NetworkGraph g = build_graph(lines);
  std::vector<char> terminal(g.nodes().size(), 0);
  auto node = [&](LonLat p) { return *g.nearest(p, 1); };
  for (LonLat p : {LonLat{0, 0}, LonLat{3, 0}, LonLat{1, 1}, LonLat{2, -1}})
    terminal[node(p)] = 1;
  const ReducedGraph r = reduce_graph(g, terminal);
  auto rn = [&](LonLat p) { return uint32_t(r.reduced_node[node(p)]); };
  Progress quiet(ProgressMode::kQuiet);
  const auto routes =
      route_connections(r, {{rn({0, 0}), rn({3, 0})}, {rn({1, 1}), rn({2, -1})}}, 1, quiet);
  const BundleSet set = make_bundles(r, routes, {10, 5});
  ASSERT_EQ(set.bundles.size(), 5u);  // 2 + 2 own legs, 1 shared
  ASSERT_EQ(set.paths[0].size(), 3u);
  ASSERT_EQ(set.paths[1].size(), 3u);
  EXPECT_EQ(set.paths[0][1], set.paths[1][1]);
  const Bundle& shared = set.bundles[set.paths[0][1]];
  EXPECT_EQ(shared.count, 2u);
  EXPECT_DOUBLE_EQ(shared.weight, 15);
  EXPECT_EQ(shared.nodes.size(), 3u);  // X, the bend, Y: the network's polyline
}

// Distance from p to the whole polyline (brute force).
double distance_to(const std::vector<XY>& poly, XY p) {
  double best = std::hypot(p.x - poly[0].x, p.y - poly[0].y);
  for (size_t i = 1; i < poly.size(); ++i) {
    const XY a = poly[i - 1], b = poly[i];
    const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
    const double t =
        len2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, std::hypot(p.x - a.x - t * dx, p.y - a.y - t * dy));
  }
  return best;
}

std::vector<XY> random_walk(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> turn(-1.2, 1.2), step(50, 400);
  std::vector<XY> poly{{0, 0}};
  double heading = 0;
  for (int i = 1; i < n; ++i) {
    heading += turn(rng);
    const double s = step(rng);
    poly.push_back({poly.back().x + s * std::cos(heading), poly.back().y + s * std::sin(heading)});
  }
  return poly;
}

TEST(BundleCurve, CurvesStayWithinTheCorridorAtEveryZoomAndKeepTheirEnds) {
  for (uint32_t seed = 1; seed <= 12; ++seed) {
    const std::vector<XY> poly = random_walk(20 + int(seed) * 15, seed);
    // Zoom z: a corridor of 4 "px" of 2^(12 - z) units.
    const int min_zoom = 0, max_zoom = 12;
    std::vector<double> tol, step;
    for (int z = 0; z <= max_zoom; ++z) {
      tol.push_back(4.0 * std::exp2(12 - z));
      step.push_back(2.0 * std::exp2(12 - z));
    }
    const auto levels = smooth_bundle(poly, min_zoom, max_zoom, tol, step);
    uint32_t covered = 0;
    for (const CurveLevel& level : levels) {
      EXPECT_EQ(covered & level.zooms, 0u) << "zooms in two levels";
      covered |= level.zooms;
      const int finest = 31 - std::countl_zero(level.zooms);
      const int coarsest = std::countr_zero(level.zooms);
      double worst = 0;
      for (const XY& p : level.curve)
        worst = std::max(worst, distance_to(poly, p));
      // Drawn with the samples it was checked with at its finest zoom.
      EXPECT_LE(worst, tol[size_t(finest)] * 1.0001 + 1e-9)
          << "seed " << seed << " zooms " << coarsest << ".." << finest;
      EXPECT_EQ(level.curve.front(), poly.front());
      EXPECT_EQ(level.curve.back(), poly.back());
    }
    // The coarsest level smooths: some vertex of the network is off its curve.
    double off = 0;
    for (const XY& v : poly)
      off = std::max(off, distance_to(levels.front().curve, v));
    EXPECT_GT(off, 1.0) << "seed " << seed;
    EXPECT_EQ(covered, (1u << (max_zoom + 1)) - 1);
  }
}

TEST(BundleCurve, AZeroCorridorGivesThePolylineAndAWideOneAStraightishCurve) {
  const std::vector<XY> poly = random_walk(40, 99);
  const std::vector<double> zero(1, 0.0), step(1, 10.0);
  const auto exact = smooth_bundle(poly, 0, 0, zero, step);
  ASSERT_EQ(exact.size(), 1u);
  for (const XY& p : exact[0].curve)
    EXPECT_LT(distance_to(poly, p), 1e-6);
  for (const XY& v : poly)  // every vertex is on the curve: it is the polyline
    EXPECT_LT(distance_to(exact[0].curve, v), 1e-6);
  // A corridor wider than the whole walk: the two ends suffice (a straight
  // line between them, sampled).
  const std::vector<double> wide(1, 1e9);
  const auto loose = smooth_bundle(poly, 0, 0, wide, step);
  ASSERT_EQ(loose.size(), 1u);
  for (const XY& p : loose[0].curve)
    EXPECT_LT(distance_to({poly.front(), poly.back()}, p), 1e-6);
}

// The direction of a sampled curve's first step (or, at_end, its last).
XY end_direction(const std::vector<XY>& c, bool at_end) {
  const XY a = at_end ? c[c.size() - 2] : c[0], b = at_end ? c.back() : c[1];
  const double len = std::hypot(b.x - a.x, b.y - a.y);
  return {(b.x - a.x) / len, (b.y - a.y) / len};
}

double angle_deg(XY a, XY b) {
  return std::acos(std::clamp(a.x * b.x + a.y * b.y, -1.0, 1.0)) * 180 / M_PI;
}

// Two bundles meeting at a node at about 40 degrees, a light branch leaving
// there too: with junction tangents the curve of the first arrives in the
// direction the second leaves (no kink), both still within their corridor;
// without, they meet at an angle.
TEST(BundleCurve, BundlesMeetingAtAJunctionShareItsTangent) {
  const std::vector<std::vector<XY>> polys = {{{-1000, 0}, {-500, 100}, {-200, -60}, {0, 0}},
                                              {{0, 0}, {400, 300}, {700, 500}, {1000, 800}},
                                              {{0, 0}, {100, -600}}};
  const std::vector<std::pair<uint32_t, uint32_t>> ends = {{0, 1}, {1, 2}, {1, 3}};
  const std::vector<double> weights = {10, 10, 1};
  const auto tangents = junction_tangents(polys, ends, weights);
  ASSERT_EQ(tangents.size(), 3u);
  EXPECT_EQ(tangents[0].first, (XY{0, 0})) << "node 0 ends one bundle: free";
  EXPECT_LT(angle_deg(tangents[0].second, tangents[1].first), 1e-4);
  const std::vector<double> tol(1, 150.0), step(1, 1.0);
  auto curve = [&](size_t b, bool tangent) {
    const auto levels =
        smooth_bundle(polys[b], 0, 0, tol, step, tangent ? tangents[b].first : XY{0, 0},
                      tangent ? tangents[b].second : XY{0, 0});
    EXPECT_EQ(levels.size(), 1u);
    for (const XY& p : levels[0].curve)
      EXPECT_LE(distance_to(polys[b], p), tol[0] * 1.0001);
    return levels[0].curve;
  };
  const auto a = curve(0, true), b = curve(1, true);
  EXPECT_EQ(a.back(), b.front());
  // (Directions of the first and last sampled steps: within a few degrees.)
  EXPECT_LT(angle_deg(end_direction(a, true), end_direction(b, false)), 3.0);
  EXPECT_LT(angle_deg(end_direction(a, true), tangents[0].second), 3.0);
  const auto free_a = curve(0, false), free_b = curve(1, false);
  EXPECT_GT(angle_deg(end_direction(free_a, true), end_direction(free_b, false)), 20.0)
      << "the junction was not a kink to begin with";
}

// A heavy flow, a light one beside it, a light one alone far away and a
// tiny one: the light neighbour shows only once zooms separate it from the
// heavy flow's view (and at the finest zoom), the lone one as soon as a view
// around it no longer reaches the heavy one, the tiny one never
// (--min-weight); without a share, all but the tiny one everywhere.
TEST(BundleSignificance, LightFlowsShowWhereNothingHeavyIsInView) {
  const tileformat::Tiling t = tileformat::Tiling::geodetic();
  const std::vector<WeightedFlow> flows = {{1000, {{{0, 10}, {20, 10}}}},
                                           {10, {{{0, 10.5}, {20, 10.5}}}},
                                           {10, {{{100, -40}, {110, -40}}}},
                                           {1, {{{-50, 0}, {-40, 0}}}}};
  const int max_zoom = 12;
  const uint32_t all = (2u << max_zoom) - 1;
  const auto z = significant_zooms(flows, t, 0, max_zoom, {0.05, 5});
  EXPECT_EQ(z[0], all);
  EXPECT_EQ(z[2], all & ~7u) << "5 x 3 tiles of zoom 2 reach the heavy flow, of zoom 3 not";
  EXPECT_EQ(z[3], 0u);
  EXPECT_FALSE(z[1] & 1u) << "beside the heavy flow at zoom 0";
  EXPECT_TRUE(z[1] >> max_zoom & 1u) << "every flow shows at the finest zoom";
  const int first = std::countr_zero(z[1]);
  EXPECT_GT(first, 6);
  EXPECT_EQ(z[1], all & ~((1u << first) - 1)) << "once shown, shown at every finer zoom";
  // Across the antimeridian, the window wraps: a light flow at 179.9 E next
  // to a heavy one at 179.9 W is hidden at zoom 3.
  const std::vector<WeightedFlow> wrap = {{1000, {{{-179.9, 0}, {-179.5, 0}}}},
                                          {10, {{{179.5, 0}, {179.9, 0}}}}};
  EXPECT_FALSE(significant_zooms(wrap, t, 0, max_zoom, {0.05, 0})[1] >> 3 & 1u);
  const auto off = significant_zooms(flows, t, 0, max_zoom, {0, 5});
  EXPECT_EQ(off, (std::vector<uint32_t>{all, all, all, 0}));
}

}  // namespace
}  // namespace globe
