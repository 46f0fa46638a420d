// The metadata every raster package (terrain, imagery) carries
// (docs/tileformat.md §3.2): the MBTiles 1.3 keys, the tiling, the format
// version, generator, command line and inputs. Builders add their own keys.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "metadata_text.hpp"
#include "tileformat/tiling.hpp"

namespace globe {

struct RasterMetadata {
  std::string output;  // package path: `name` is its stem
  std::string format;  // MBTiles `format`
  std::string
      description;  // e.g. "Terrain (MBlock/KPatch)"; " built by globe-tiler from ..." follows
  std::vector<std::pair<std::string, unsigned long long>> inputs;  // path, bytes
  tileformat::Tiling tiling;
  tileformat::Bounds lonlat;
  int min_zoom = 0, max_zoom = 0;
  std::string resampling, command_line;
  std::string left_out;    // Footprint::left_out
  int bounds_digits = 10;  // significant digits of `bounds` (0: exact)
};

std::map<std::string, std::string> raster_metadata(const RasterMetadata& m);

}  // namespace globe
