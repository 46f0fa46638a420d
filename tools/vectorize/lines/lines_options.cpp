// Line tile options (see lines_options.hpp).
#include "lines/lines_options.hpp"

#include "runtime/errors.hpp"

namespace globe {

void declare_line_tile_options(CliArgs& cli, LinesSettings& s) {
  cli.option(
      "--style", "CLASS:K=V,...",
      "a class's style (repeatable); keys color=#rrggbb (or slope[:RAMP.txt],\n"
      "                              height[:RAMP.txt]: by the ground under the line, in\n"
      "                              globe-view), width=2px|12m, casing=#rrggbb@1px, dash=6+3,\n"
      "                              opacity=0.5,\n"
      "                              pattern=railway|arrows|zigzag|dots[@SPACING] (default:\n"
      "                              palette, 1.5px, solid, opaque, no pattern)",
      [&](const std::string& v) { s.styles.push_back(v); });
  cli.option("--cluster-grid", "C", "cluster cells per tile side (default 32)",
             [&](const std::string& v) {
               s.cluster_grid = CliArgs::to_int("--cluster-grid", v, 1, 256);
               if (4096 % s.cluster_grid != 0)
                 throw UsageError("--cluster-grid must divide 4096 (1, 2, 4, ... 256)");
             });
  cli.option("--simplify", "PX",
             "Douglas-Peucker tolerance in pixels of each zoom (default 0.25; 0 = off)",
             [&](const std::string& v) {
               s.simplify_px = CliArgs::to_double("--simplify", v);
               if (s.simplify_px < 0 || s.simplify_px > 16)
                 throw UsageError("--simplify must be within 0..16 pixels");
             });
  cli.option("--memory-mb", "MB",
             "memory for sorting tile pieces before spilling to disk (default 256)",
             [&](const std::string& v) {
               s.memory_mb = static_cast<size_t>(CliArgs::to_int("--memory-mb", v, 1, 1 << 20));
             });
}

}  // namespace globe
