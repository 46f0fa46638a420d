// Routing (see routing.hpp).
#include "bundle/routing.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numbers>

#include "parallel_batches.hpp"

namespace globe {

namespace {

// One worker's search state, reset between searches by a generation stamp
// rather than cleared; a node's state in one place (one cache line).
struct NodeState {
  double cost = 0;    // from the origin
  double h = 0;       // the heuristic (set when first seen)
  uint32_t via = 0;   // the edge it was reached by
  uint32_t seen = 0;  // generation when cost/via were set
  uint32_t done = 0;  // generation when settled
  uint32_t h_at = 0;  // the goal phase h was computed for
};
struct Search {
  std::vector<NodeState> node;
  std::vector<std::pair<double, uint32_t>> heap;  // (cost + h, node), a min-heap
  uint32_t generation = 0;                        // one per search
  uint32_t phase = 0;                             // one per goal of a search
  explicit Search(size_t n) : node(n) {}
};

// The heuristic's sphere: a radius short of the Earth's smallest, so the
// chord between two points there is shorter than any geodesic between them
// on WGS84 (and than any path of the network). A chord is a metric, so the
// heuristic (the chord to the nearest target) is consistent.
constexpr double kLowRadius = 6356752.0 * 0.99;

std::array<double, 3> on_sphere(LonLat p) {
  const double lon = p.lon * std::numbers::pi / 180, lat = p.lat * std::numbers::pi / 180;
  return {kLowRadius * std::cos(lat) * std::cos(lon), kLowRadius * std::cos(lat) * std::sin(lon),
          kLowRadius * std::sin(lat)};
}

}  // namespace

std::vector<std::vector<uint32_t>> route_connections(const ReducedGraph& g,
                                                     const std::vector<OriginDestination>& od,
                                                     std::span<const LonLat> positions, int threads,
                                                     Progress& progress) {
  std::map<uint32_t, std::vector<uint32_t>> by_origin;  // origin -> its connections
  for (uint32_t c = 0; c < od.size(); ++c)
    if (od[c].origin != od[c].destination) by_origin[od[c].origin].push_back(c);
  std::vector<std::pair<uint32_t, const std::vector<uint32_t>*>> origins;
  for (const auto& [o, cs] : by_origin)
    origins.emplace_back(o, &cs);

  const size_t n = g.graph_node.size();
  threads = std::max(1, threads);
  // Each node's arcs side by side (the search reads nothing else).
  struct Arc {
    double cost;
    uint32_t to, edge;
  };
  std::vector<Arc> arcs(g.incident.size());
  for (uint32_t v = 0; v < n; ++v)
    for (uint32_t k = g.offsets[v]; k < g.offsets[v + 1]; ++k) {
      const ReducedGraph::Edge& e = g.edges[g.incident[k]];
      arcs[k] = {e.cost, e.a == v ? e.b : e.a, g.incident[k]};
    }
  // The heuristic's points: each reduced node on a sphere of kLowRadius.
  std::vector<std::array<double, 3>> unit;
  if (!positions.empty())
    for (uint32_t v = 0; v < n; ++v)
      unit.push_back(on_sphere(positions[g.graph_node[v]]));
  std::vector<Search> searches;
  searches.reserve(size_t(threads));
  for (int t = 0; t < threads; ++t)
    searches.emplace_back(n);
  std::vector<std::vector<uint32_t>> routes(od.size());
  using Routes = std::vector<std::pair<uint32_t, std::vector<uint32_t>>>;
  progress.begin("route connections", origins.size());
  parallel_batches<NoInputs, Routes>(
      origins.size(), threads, std::max<size_t>(16, size_t(threads) * 4),
      [](size_t, size_t) { return NoInputs{}; },
      [&](size_t i, int worker, const NoInputs&) {
        Search& s = searches[size_t(worker)];
        const uint32_t gen = ++s.generation;
        const uint32_t origin = origins[i].first;
        const std::vector<uint32_t>& conns = *origins[i].second;
        // The destinations still to settle.
        std::vector<uint32_t> targets;
        for (uint32_t c : conns)
          targets.push_back(od[c].destination);
        std::sort(targets.begin(), targets.end());
        targets.erase(std::unique(targets.begin(), targets.end()), targets.end());
        // The targets nearest first (chord from the origin); each in turn is
        // the goal of an A* search (h: the chord to it, 0 without positions).
        // The closed set carries over from goal to goal (its costs are final
        // for any consistent heuristic); the open set is re-keyed.
        auto chord = [&](uint32_t a, uint32_t b) {
          const double dx = unit[a][0] - unit[b][0], dy = unit[a][1] - unit[b][1],
                       dz = unit[a][2] - unit[b][2];
          return std::sqrt(dx * dx + dy * dy + dz * dz);
        };
        if (!unit.empty())
          std::sort(targets.begin(), targets.end(), [&](uint32_t a, uint32_t b) {
            const double da = chord(origin, a), db = chord(origin, b);
            return da != db ? da < db : a < b;
          });
        auto& heap = s.heap;
        const auto later = std::greater<>();
        heap.clear();
        uint32_t goal = targets.front();
        auto h = [&](uint32_t v, NodeState& sv) {
          if (sv.h_at != s.phase) {
            sv.h = unit.empty() ? 0 : chord(v, goal);
            sv.h_at = s.phase;
          }
          return sv.h;
        };
        ++s.phase;
        NodeState& start = s.node[origin];
        start.cost = 0;
        start.via = std::numeric_limits<uint32_t>::max();
        start.seen = gen;
        heap.push_back({h(origin, start), origin});
        for (const uint32_t target : targets) {
          if (s.node[target].done == gen) continue;  // closed on the way to another
          if (target != goal) {
            goal = target;
            if (!unit.empty()) {  // re-key the open set for the new goal
              ++s.phase;
              std::vector<std::pair<double, uint32_t>> open;
              open.reserve(heap.size());
              for (const auto& [f, w] : heap) {
                NodeState& sw = s.node[w];
                if (sw.done == gen || sw.h_at == s.phase) continue;  // closed, or had
                open.push_back({sw.cost + h(w, sw), w});
              }
              heap.swap(open);
              std::make_heap(heap.begin(), heap.end(), later);
            }
          }
          while (!heap.empty() && s.node[goal].done != gen) {
            std::pop_heap(heap.begin(), heap.end(), later);
            const uint32_t v = heap.back().second;
            heap.pop_back();
            // The first time v comes out is with its least cost (h is the
            // same for all its entries); later entries are stale.
            NodeState& sv = s.node[v];
            if (sv.done == gen) continue;
            sv.done = gen;
            const double c = sv.cost;
            for (uint32_t k = g.offsets[v]; k < g.offsets[v + 1]; ++k) {
              const Arc& arc = arcs[k];
              NodeState& sw = s.node[arc.to];
              if (sw.done == gen) continue;
              const double nc = c + arc.cost;
              if (sw.seen != gen || nc < sw.cost) {
                sw.seen = gen;
                sw.cost = nc;
                sw.via = arc.edge;
                heap.push_back({nc + h(arc.to, sw), arc.to});
                std::push_heap(heap.begin(), heap.end(), later);
              }
            }
          }
          if (heap.empty()) break;  // the rest is not reachable
        }
        Routes out;
        for (uint32_t c : conns) {
          std::vector<uint32_t> path;
          uint32_t v = od[c].destination;
          if (s.node[v].done == gen) {
            while (v != origin) {
              const uint32_t e = s.node[v].via;
              path.push_back(e);
              v = g.edges[e].a == v ? g.edges[e].b : g.edges[e].a;
            }
            std::reverse(path.begin(), path.end());
          }
          out.emplace_back(c, std::move(path));
        }
        return out;
      },
      [&](size_t, Routes&& r) {
        for (auto& [c, path] : r)
          routes[c] = std::move(path);
        progress.advance();
      },
      [](size_t) {});
  progress.end();
  return routes;
}

}  // namespace globe
