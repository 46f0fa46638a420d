// Common raster package metadata (see raster_metadata.hpp).
#include "raster/raster_metadata.hpp"

#include <algorithm>
#include <filesystem>

namespace globe {

tileformat::CommonMetadata raster_common_metadata(const RasterPackageFacts& facts,
                                                  std::vector<tileformat::InputFile> inputs,
                                                  const Footprint& footprint) {
  tileformat::CommonMetadata m;
  m.name = std::filesystem::path(facts.output).stem().string();
  m.format = facts.format;
  m.type = "baselayer";
  m.description = tileformat::build_description(facts.what, "globe-tiler", inputs);
  m.lonlat = footprint.lonlat;
  // A dataset smaller than one pixel of the coarsest zooms leaves them empty
  // (empty tiles are not written): minzoom says what is there.
  m.min_zoom = facts.min_zoom;
  m.max_zoom = facts.max_zoom;
  m.center_zoom = raster_center_zoom(footprint, facts.min_zoom, facts.max_zoom);
  m.tiling = footprint.tiling;
  m.generator = "globe-tiler " GLOBE_VERSION;
  m.command_line = facts.command_line;
  m.inputs = std::move(inputs);
  m.left_out = footprint.left_out;
  return m;
}

int raster_center_zoom(const Footprint& footprint, int min_zoom, int max_zoom) {
  tileformat::Bounds data{1e300, 1e300, -1e300, -1e300};
  for (const tileformat::Bounds& a : footprint.data_areas)
    data = {std::min(data.min_x, a.min_x), std::min(data.min_y, a.min_y),
            std::max(data.max_x, a.max_x), std::max(data.max_y, a.max_y)};
  return footprint.tiling.view_zoom(data, min_zoom, max_zoom);
}

}  // namespace globe
