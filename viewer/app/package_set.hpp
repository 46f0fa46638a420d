// Which of the command line's packages is the terrain, the imagery and the lines:
// sorted by their `format` metadata, checked for a common tiling.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "camera/layer_tiling.hpp"
#include "tileformat/tiling.hpp"

namespace globe::viewer {

struct PackageSet {
  std::string terrain;  // "" when none is given: lines, points or imagery over a flat base
  std::vector<std::string> images;  // in command-line order: the first is the bottom layer
  std::optional<std::string> lines;
  std::optional<std::string> analysis;  // terrain analytics (globe-tiler analyze)
  std::optional<std::string> points;    // places for charts (globe-vectorize points)
  std::optional<std::string> areas;     // polygons (globe-vectorize areas)
};

// Throws InputError (a package that is missing or of an unknown kind) or
// UsageError (nothing to draw, an analysis without its terrain, two
// terrains, two line, analysis, point or area packages).
PackageSet sort_packages(const std::vector<std::string>& paths);

// Throws InputError naming both files unless `other` uses the terrain's
// tiling scheme, CRS, origin and root size.
void check_same_tiling(const tileformat::Tiling& terrain, const std::string& terrain_path,
                       const tileformat::Tiling& other, const std::string& other_path);

// How the terrain's CRS reaches a line or point package's tiling: the same
// tiling, or geodetic <-> webmercator either way. Throws InputError naming
// both files for any other pair (local tilings must match).
CrsCross layer_cross(const tileformat::Tiling& terrain, const std::string& terrain_path,
                     const tileformat::Tiling& other, const std::string& other_path);

}  // namespace globe::viewer
