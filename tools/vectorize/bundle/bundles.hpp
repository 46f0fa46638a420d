// Bundles (docs/bundles.md "Bundles"): maximal chains of network edges that
// carry the same set of connections. A routed connection is then a sequence
// of bundles; each bundle carries its connections' total weight and count,
// and its geometry is the chain's network polyline.
#pragma once

#include <cstdint>
#include <vector>

#include "bundle/network_graph.hpp"

namespace globe {

struct Bundle {
  std::vector<uint32_t> nodes;  // graph nodes along the chain, end to end
  double weight = 0;            // total weight of its connections
  uint32_t count = 0;           // its connections
  double length_m = 0;          // along the network
};

struct BundleSet {
  std::vector<Bundle> bundles;
  // Per connection: its bundles in path order (empty when not routed).
  std::vector<std::vector<uint32_t>> paths;
};

// `routes`: per connection, its reduced edges from origin to destination
// (routing.hpp); `weights`: per connection. Bundles are numbered in the
// order of their first reduced edge, so the result depends only on the input.
BundleSet make_bundles(const ReducedGraph& g, const std::vector<std::vector<uint32_t>>& routes,
                       const std::vector<double>& weights);

}  // namespace globe
