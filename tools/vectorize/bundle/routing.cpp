// Routing (see routing.hpp).
#include "bundle/routing.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <queue>

#include "parallel_batches.hpp"

namespace globe {

namespace {

// One worker's search state, reset between searches by a generation stamp
// rather than cleared.
struct Search {
  std::vector<double> cost;
  std::vector<uint32_t> via;   // the edge a node was reached by
  std::vector<uint32_t> seen;  // generation when cost/via were set
  std::vector<uint32_t> done;  // generation when settled
  uint32_t generation = 0;
  explicit Search(size_t n) : cost(n), via(n), seen(n, 0), done(n, 0) {}
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
        size_t left = targets.size();
        using Item = std::pair<double, uint32_t>;
        std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
        s.cost[origin] = 0;
        s.seen[origin] = gen;
        s.via[origin] = std::numeric_limits<uint32_t>::max();
        queue.push({0, origin});
        while (!queue.empty() && left > 0) {
          const auto [c, v] = queue.top();
          queue.pop();
          if (s.done[v] == gen || c > s.cost[v]) continue;
          s.done[v] = gen;
          if (std::binary_search(targets.begin(), targets.end(), v)) --left;
          for (uint32_t k = g.offsets[v]; k < g.offsets[v + 1]; ++k) {
            const uint32_t e = g.incident[k];
            const ReducedGraph::Edge& edge = g.edges[e];
            const uint32_t w = edge.a == v ? edge.b : edge.a;
            const double nc = c + edge.cost;
            if (s.done[w] == gen) continue;
            if (s.seen[w] != gen || nc < s.cost[w]) {
              s.seen[w] = gen;
              s.cost[w] = nc;
              s.via[w] = e;
              queue.push({nc, w});
            }
          }
        }
        Routes out;
        for (uint32_t c : conns) {
          std::vector<uint32_t> path;
          uint32_t v = od[c].destination;
          if (s.done[v] == gen) {
            while (v != origin) {
              const uint32_t e = s.via[v];
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
