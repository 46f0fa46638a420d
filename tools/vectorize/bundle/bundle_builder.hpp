// Builds a package of bundled flows (docs/bundles.md): the connections of
// FLOWS routed over the reference network, bundled, smoothed and written as a
// line-cluster package (line_tiles.hpp) whose features are the bundles (class
// weight-1 .. weight-N by weight), the unrouted connections drawn straight
// (class unrouted), and a row per connection naming its bundles.
//
// Stages: read the network (network_graph.hpp), read the flows
// (flow_input.hpp), snap places to nodes, reduce the graph, route
// (routing.hpp), bundle (bundles.hpp), smooth (bundle_curve.hpp), cut and
// encode tiles. Each stage is deterministic for any thread count.
#pragma once

#include "kit/package_output.hpp"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "bundle/bundle_settings.hpp"
#include "kit/progress.hpp"

namespace globe {

struct BundleSummary : PackageSummary {
  uint64_t rows = 0, connections = 0, bad_rows = 0, zero_weights = 0;
  uint64_t routed = 0, unrouted = 0, bundles = 0;
  uint64_t unsnapped = 0, same_node = 0, disconnected = 0;  // unrouted, by reason
  uint64_t network_nodes = 0, network_edges = 0, components = 0;
  uint64_t reduced_nodes = 0, reduced_edges = 0, curve_levels = 0, curve_points = 0;
  double mean_detour = 0, ink_ratio = 0;
  uint64_t hidden_at_min_zoom = 0;  // flows the significance filter hides at the coarsest zoom
  uint64_t never_drawn = 0;         // flows lighter than --min-weight
  int min_zoom = 0, max_zoom = 0;
  std::vector<std::string> bad_row_examples;
  std::vector<std::pair<std::string, double>> stage_seconds;  // in order
};

BundleSummary build_bundles(const BundleSettings& settings, Progress& progress);

}  // namespace globe
