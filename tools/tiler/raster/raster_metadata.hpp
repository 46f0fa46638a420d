// The keys every raster package (terrain, imagery) shares, from a raster
// plan: the package name from the output path, the inputs with their sizes,
// the description globe-tiler writes. Builders add their kind's keys to the
// typed metadata of lib/tileformat (metadata.hpp), which writes them.
#pragma once

#include <string>
#include <vector>

#include "raster/raster_footprint.hpp"
#include "tileformat/metadata.hpp"

namespace globe {

struct RasterPackageFacts {
  std::string output;  // package path: `name` is its stem
  std::string format;  // MBTiles `format`
  std::string what;    // e.g. "Terrain (MBlock/KPatch)", the start of `description`
  std::string command_line;
  int min_zoom = 0, max_zoom = 0;
};

// The common metadata of a package built from `inputs` placed by
// `footprint` (its tiling, lon/lat bounds and what it left out).
tileformat::CommonMetadata raster_common_metadata(const RasterPackageFacts& facts,
                                                  std::vector<tileformat::InputFile> inputs,
                                                  const Footprint& footprint);

// The zoom of `center`: where the data's extent fills a view, within
// min_zoom..max_zoom.
int raster_center_zoom(const Footprint& footprint, int min_zoom, int max_zoom);

}  // namespace globe
