// Routing (see routing.hpp).
#include "bundle/routing.hpp"

#include <algorithm>
#include <functional>
#include <limits>
#include <map>
#include <string>

#include "kit/parallel_batches.hpp"

namespace globe {

namespace {

// One worker's search state, reset between searches by a generation stamp
// rather than cleared; a node's state in one place (one cache line).
struct NodeState {
  double cost = 0;      // from the origin
  uint32_t via = 0;     // the edge it was reached by
  uint32_t seen = 0;    // generation when cost/via were set
  uint32_t done = 0;    // generation when settled
  uint32_t target = 0;  // generation in which it is a destination still to settle
};
struct Search {
  std::vector<NodeState> node;
  std::vector<std::pair<double, uint32_t>> heap;  // (cost, node), a min-heap
  uint32_t generation = 0;                        // one per search
  explicit Search(size_t n) : node(n) {}
};

}  // namespace

std::vector<std::vector<uint32_t>> route_connections(const ReducedGraph& g,
                                                     const std::vector<OriginDestination>& od,
                                                     int threads, Progress& progress) {
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
        size_t left = 0;
        for (uint32_t c : conns) {
          NodeState& t = s.node[od[c].destination];
          if (t.target != gen) t.target = gen, ++left;
        }
        auto& heap = s.heap;
        const auto later = std::greater<>();
        heap.clear();
        NodeState& start = s.node[origin];
        start.cost = 0;
        start.via = std::numeric_limits<uint32_t>::max();
        start.seen = gen;
        heap.push_back({0, origin});
        while (!heap.empty() && left > 0) {
          std::pop_heap(heap.begin(), heap.end(), later);
          const uint32_t v = heap.back().second;
          heap.pop_back();
          // The first time v comes out is with its least cost; later
          // entries are stale.
          NodeState& sv = s.node[v];
          if (sv.done == gen) continue;
          sv.done = gen;
          if (sv.target == gen) --left;
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
              heap.push_back({nc, arc.to});
              std::push_heap(heap.begin(), heap.end(), later);
            }
          }
        }
        Routes out;
        for (uint32_t c : conns) {
          std::vector<uint32_t> path;
          uint32_t v = od[c].destination;
          if (s.node[v].done == gen) {
            // Each step goes to a node settled earlier, so a path has fewer
            // edges than the graph has nodes; more means the graph's
            // adjacency is inconsistent (an edge listed at a node it does
            // not touch): an internal error naming the connection, never an
            // endless walk.
            while (v != origin) {
              const uint32_t e = s.node[v].via;
              const ReducedGraph::Edge& edge = g.edges[e];
              if (path.size() >= n || (edge.a != v && edge.b != v))
                throw RouteError(c, "the path back from node " + std::to_string(od[c].destination) +
                                        " does not reach its origin " + std::to_string(origin) +
                                        " (edge " + std::to_string(e) + " after " +
                                        std::to_string(path.size()) + " steps)");
              path.push_back(e);
              v = edge.a == v ? edge.b : edge.a;
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
