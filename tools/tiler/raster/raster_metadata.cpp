// Common raster package metadata (see raster_metadata.hpp).
#include "raster_metadata.hpp"

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
  m.center_zoom = facts.max_zoom;
  m.tiling = footprint.tiling;
  m.generator = "globe-tiler " GLOBE_VERSION;
  m.command_line = facts.command_line;
  m.inputs = std::move(inputs);
  m.left_out = footprint.left_out;
  return m;
}

}  // namespace globe
