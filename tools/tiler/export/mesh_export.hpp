// `globe-tiler export TERRAIN --format quantized-mesh` (docs/web.md
// "Quantized-mesh"): a geodetic or webmercator terrain package as CesiumJS
// terrain, DIR/layer.json + DIR/{z}/{x}/{y}.terrain (TMS rows) or one
// MBTiles file holding the .terrain tiles and layer.json. Two passes over the
// tiles: the first keeps each tile's half errors of its edge vertices (4
// floats per edge sample), the second cuts each tile's TIN with its
// neighbours' halves joined, so neighbours share their border vertices.
#pragma once

#include <string>

#include "dem_export.hpp"
#include "progress.hpp"

namespace globe {

struct MeshExportSettings {
  std::string input, output;
  int threads = 1;
  bool force = false;
  bool gzip = false;          // gzip each tile (servers then send Content-Encoding: gzip)
  bool normals = true;        // extension octvertexnormals
  double error_scale = 1.0;   // of CesiumJS's geometric error per level
  double finest_error = 2.0;  // metres, at the package's finest zoom
};

ExportSummary export_quantized_mesh(const MeshExportSettings& s, Progress& progress);

}  // namespace globe
