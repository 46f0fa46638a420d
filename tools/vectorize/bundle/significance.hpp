// The significance filter of bundled flows (docs/bundles.md "Weights and
// styles"): at each zoom, a flow (a bundle or an unrouted line) is drawn only
// if it carries at least `share` of the heaviest flow in a view around it,
// so a continental view shows the main corridors and each zoom in lets the
// lighter flows of that area appear. The view is a window of 5 x 3 tiles
// (about 1280 x 720 px) centred on each tile the flow crosses; the flow is
// significant where the lightest such window is, so a flow through an empty
// area stays. Once significant, a flow stays at every finer zoom; at the
// finest zoom every flow shows, except those lighter than `min_weight`,
// which never do.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "lines/line_geometry.hpp"
#include "tileformat/tiling.hpp"

namespace globe {

struct WeightedFlow {
  double weight = 0;
  std::vector<std::vector<XY>> parts;  // in the tiling's CRS; longitudes may be unrolled
};

struct SignificanceOptions {
  double share = 0;       // 0: every flow at every zoom
  double min_weight = 0;  // lighter flows never show
};

// Per flow, the zooms it is drawn at (bit z), within min_zoom..max_zoom.
std::vector<uint32_t> significant_zooms(std::span<const WeightedFlow> flows,
                                        const tileformat::Tiling& tiling, int min_zoom,
                                        int max_zoom, const SignificanceOptions& options);

}  // namespace globe
