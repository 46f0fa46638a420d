// Routing connections over the reduced network (docs/bundles.md "Routing"):
// one search per distinct origin, searches spread over threads. With node
// positions (costs in metres) a search takes its destinations nearest first,
// each the goal of A* (h: the chord to it on a sphere inside the ellipsoid,
// a consistent lower bound), keeping the closed set from goal to goal and
// re-keying the open one; without positions it is Dijkstra. Either way it
// stops once every destination is settled. A search is sequential and
// breaks ties by node id (the queue orders by key, then node; a node's
// predecessor changes only for a strictly cheaper cost), so routes never
// depend on the thread count.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "bundle/network_graph.hpp"
#include "progress.hpp"

namespace globe {

struct OriginDestination {
  uint32_t origin = 0, destination = 0;  // reduced nodes
};

// Per connection: the reduced edges from origin to destination in path
// order (empty when they are not connected, or are the same node).
// `positions`: the graph's nodes (NetworkGraph::nodes()) when edge costs are
// geodesic lengths; empty for other costs.
std::vector<std::vector<uint32_t>> route_connections(const ReducedGraph& g,
                                                     const std::vector<OriginDestination>& od,
                                                     std::span<const LonLat> positions, int threads,
                                                     Progress& progress);

}  // namespace globe
