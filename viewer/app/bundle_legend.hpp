// The legend of a bundled-flows package (docs/bundles.md "Viewer"): one row
// per weight class, its stroke (width, colour and opacity of the class's
// style, as drawn) and the weights it holds, from the package's globe:bundle
// metadata; queued into a TextOverlay in the bottom-left corner.
#pragma once

#include <string>
#include <vector>

#include "render/text_overlay.hpp"
#include "runtime/line_style.hpp"

namespace globe::viewer {

struct LegendRow {
  std::string class_name;  // "weight-3"
  double min = 0, max = 0;
};

// The rows of globe:bundle's "weight_classes" (none when absent or not JSON).
std::vector<LegendRow> bundle_legend_rows(const std::string& bundle_json);

// "533k", "1.2M", "71", "0.5": a weight in at most four characters or so.
std::string short_weight(double w);

// One row of a legend box: a stroke `line_px` wide in its colour, or (0) a
// swatch, and its label.
struct LegendEntry {
  glm::vec4 color;
  float line_px = 0;
  std::string label;
};

// A legend box in the bottom-left corner of a `height`-pixel frame: the
// title, then a row per entry, its mark `mark_units` font pixels wide.
void queue_legend_box(const std::string& title, const std::vector<LegendEntry>& entries,
                      float mark_units, int height, TextOverlay& overlay);

// Queues the legend for a `height`-pixel frame; rows whose class is not in
// `styles` or is hidden are left out.
void queue_bundle_legend(const std::vector<LegendRow>& rows,
                         const std::vector<NamedLineStyle>& styles, int height,
                         TextOverlay& overlay);

}  // namespace globe::viewer
