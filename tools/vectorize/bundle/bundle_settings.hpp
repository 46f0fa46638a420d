// Settings of `globe-vectorize bundle`, filled by the command-line parser and
// read by the builder (nothing here touches OGR). The line options (tiling,
// zooms, --style, cluster grid) are those of `globe-vectorize lines`.
#pragma once

#include <string>
#include <vector>

#include "bundle/flow_input.hpp"
#include "bundle/network_graph.hpp"
#include "lines/lines_settings.hpp"

namespace globe {

enum class Unrouted { kStraight, kDrop };

struct BundleSettings : LinesSettings {
  std::string flows;                 // the connections (inputs[0])
  std::vector<std::string> network;  // --network (repeatable)
  FlowOptions flow;
  NetworkOptions net;
  double max_snap_m = 25000;  // --max-snap: a place this far from every node is unrouted
  double corridor_px = 4;     // --corridor-px: the curve's distance from the network
  Unrouted unrouted = Unrouted::kStraight;
  int weight_classes = 6;                      // --weight-classes
  double min_width = 1, max_width = 9;         // --widths MIN,MAX (px) of the weight classes
  double min_opacity = 0.45, max_opacity = 1;  // --opacities MIN,MAX of the weight classes
  double significance = 0.02;    // --significance: share of the heaviest flow in view (0: off)
  double min_weight = 0;         // --min-weight: lighter flows are not drawn
  bool smooth_junctions = true;  // --no-junction-tangents turns it off
};

}  // namespace globe
