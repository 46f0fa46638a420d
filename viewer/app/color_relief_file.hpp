// Reads gdaldem color-relief colour files: one stop per line,
// "VALUE R G B [A]" or "VALUE NAME" (white, black, red, ...), separated by
// spaces, tabs, commas or colons; VALUE is a number, a percentage of the
// data range ("50%") or "nv" (no-data colour); '#' starts a comment.
#pragma once

#include <optional>
#include <string>

#include "render/color_ramp.hpp"

namespace globe::viewer {

struct ColorReliefFile {
  ColorRamp ramp;
  std::optional<Rgba> nodata;  // the "nv" line
};

// Throws UsageError naming the file and line for anything it cannot read.
ColorReliefFile read_color_relief_file(const std::string& path);

}  // namespace globe::viewer
