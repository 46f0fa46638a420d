// How charts look (docs/viewer.md "Charts"): a colour per field, the size
// range, outline, opacity, legend, and the columns' height; the defaults, and
// a style file (--chart-style) over them that the window reloads when it
// changes.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace globe::viewer {

struct ChartStyle {
  std::vector<std::string> colors;  // "#rrggbb" per field, by field index
  double min_px = 8, max_px = 48;   // chart size limits (pies: diameter)
  std::string outline = "#262626";
  double outline_px = 1;  // 0: none
  double opacity = 1;
  bool legend = true;
  double column_px = 100;  // the largest value's column height, pixels of a 256 px tile
};

// Defaults for `fields` (the line palette's colours in field order), then,
// with `path`, the style file's keys over them: a JSON object with any of
// "colors" (object: field name -> "#rrggbb"), "min_px", "max_px", "outline"
// ("#rrggbb"), "outline_px", "opacity" (0..1), "legend" (true/false),
// "column_px". Throws InputError naming the file and the key (an unknown
// key, a field the package does not have, a bad value).
ChartStyle read_chart_style(const std::vector<std::string>& fields,
                            const std::optional<std::string>& path);

}  // namespace globe::viewer
