// Routing connections over the reduced network (docs/bundles.md "Routing"):
// one Dijkstra search per distinct origin, searches spread over threads,
// each stopping once it has settled every destination its connections
// need. A search is sequential and breaks ties by node id (the queue orders
// by cost, then node; a node's predecessor changes only for a strictly
// cheaper cost), so routes never depend on the thread count.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "bundle/network_graph.hpp"
#include "kit/progress.hpp"

namespace globe {

struct OriginDestination {
  uint32_t origin = 0, destination = 0;  // reduced nodes
};

// A route that could not be rebuilt (an inconsistent graph: a bug, never
// bad input). `connection` indexes the `od` given to route_connections.
struct RouteError : std::logic_error {
  RouteError(size_t connection, const std::string& what)
      : std::logic_error(what), connection(connection) {}
  size_t connection;
};

// Per connection: the reduced edges from origin to destination in path
// order (empty when they are not connected, or are the same node). Throws
// RouteError where a path does not lead back to its origin.
std::vector<std::vector<uint32_t>> route_connections(const ReducedGraph& g,
                                                     const std::vector<OriginDestination>& od,
                                                     int threads, Progress& progress);

}  // namespace globe
