// The reference network of a bundling (docs/bundles.md "Network"): the lines
// of any OGR sources (roads, rails, airways) as a graph in longitude and
// latitude. Vertices closer than the snap tolerance are one node (a grid of
// the tolerance); each line's consecutive vertices are an edge whose cost is
// its geodesic length on the WGS84 ellipsoid (or the line's cost field,
// shared out along it by length); of parallel edges the cheaper stays. Then
// connected components, the nearest node to a place (a grid index), and the
// graph reduction: chains through nodes of degree 2 become one edge carrying
// their polyline, except through terminals (the nodes places snap to).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "kit/progress.hpp"

namespace globe {

struct LonLat {
  double lon = 0, lat = 0;
};

struct NetworkOptions {
  std::vector<std::string> layers;  // --network-layer (empty: every layer)
  std::string s_srs;                // for files without a CRS
  std::string cost_field;           // "" = geodesic length
  double snap_m = 1;                // vertices closer than this are one node
};

struct NetworkStats {
  uint64_t lines = 0, vertices = 0, nodes = 0, edges = 0, parallel = 0;
  uint64_t components = 0, largest_component = 0;  // nodes of the largest
};

class NetworkGraph {
 public:
  struct Edge {
    uint32_t a = 0, b = 0;  // nodes, a < b
    double cost = 0, length_m = 0;
  };

  // Reads the lines of `inputs`. Throws InputError for a layer of points,
  // no line at all, or a line without a CRS (UsageError for a missing or
  // text cost field).
  static NetworkGraph read(const std::vector<std::string>& inputs, const NetworkOptions& options,
                           Progress& progress);

  // Builds a graph line by line (read() uses it; so can tests).
  class Builder {
   public:
    explicit Builder(double snap_m);
    ~Builder();
    // One line's parts in longitude/latitude. `cost`: the whole line's
    // cost, shared out along it by length (NaN: its geodesic length). A
    // negative or non-finite cost leaves the line out.
    void add_line(const std::vector<std::vector<LonLat>>& parts, double cost);
    NetworkGraph finish();

   private:
    struct State;
    std::unique_ptr<State> st_;
  };

  const std::vector<LonLat>& nodes() const { return nodes_; }
  const std::vector<Edge>& edges() const { return edges_; }
  const NetworkStats& stats() const { return stats_; }
  uint32_t component(uint32_t node) const { return component_[node]; }
  // The node nearest to `p` (geodesic metres) within `max_m`, or nullopt.
  std::optional<uint32_t> nearest(LonLat p, double max_m) const;

 private:
  void index_nodes();
  void find_components();

  std::vector<LonLat> nodes_;
  std::vector<Edge> edges_;
  std::vector<uint32_t> component_;
  NetworkStats stats_;
  // Nodes in grid cells of cell_deg_ (columns_ around the globe), for nearest().
  std::unordered_map<uint64_t, std::vector<uint32_t>> cells_;
  double cell_deg_ = 1;
  int64_t columns_ = 360;
};

// The graph reduction. Reduced nodes are the graph's nodes of degree other
// than 2 and the terminals; each reduced edge is a chain of graph edges
// between two of them.
struct ReducedGraph {
  struct Edge {
    uint32_t a = 0, b = 0;  // reduced nodes
    double cost = 0, length_m = 0;
    uint32_t first = 0, count = 0;  // its graph nodes, a to b: path[first .. first + count)
  };
  std::vector<uint32_t> graph_node;   // reduced node -> graph node
  std::vector<int32_t> reduced_node;  // graph node -> reduced node (-1: inside a chain)
  std::vector<Edge> edges;
  std::vector<uint32_t> path;               // the chains' graph nodes
  std::vector<uint32_t> offsets, incident;  // CSR: each reduced node's edges
};

// `terminal[node]`: a node a place snapped to (kept as a reduced node).
ReducedGraph reduce_graph(const NetworkGraph& graph, const std::vector<char>& terminal);

}  // namespace globe
