// `globe-tiler export IMAGES -o OUT.pmtiles|OUT.mbtiles|DIR` (docs/web.md
// "Images"): an image package's tiles, byte for byte, in a web container.
// Web clients read web mercator XYZ tiles, so the package must be in the
// webmercator tiling.
#pragma once

#include <string>

#include "export/dem_export.hpp"

namespace globe {

struct ImageExportSettings {
  std::string input, output;
  bool force = false;
};

ExportSummary export_images(const ImageExportSettings& s, Progress& progress);

}  // namespace globe
