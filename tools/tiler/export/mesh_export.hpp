// `globe-tiler export TERRAIN --format quantized-mesh` (docs/web.md
// "Quantized-mesh"): a geodetic or webmercator terrain package as CesiumJS
// terrain, DIR/layer.json + DIR/{z}/{x}/{y}.terrain (TMS rows) or one
// MBTiles file holding the .terrain tiles and layer.json. One pass over the
// tiles in PMTiles order (neighbours close together): each tile is cut alone
// from the blocks of it and its eight neighbours (web/mesh_tiles.hpp), each
// worker keeping the own errors of the last 64 tiles it saw.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "export/dem_export.hpp"
#include "kit/progress.hpp"

namespace globe {

struct MeshExportSettings {
  std::string input, output;
  int threads = 1;
  bool force = false;
  bool gzip = false;          // gzip each tile (servers then send Content-Encoding: gzip)
  int gzip_level = 6;         // zlib's deflate level, 1..9
  bool normals = true;        // extension octvertexnormals
  double error_scale = 1.0;   // of CesiumJS's geometric error per level
  double finest_error = 2.0;  // metres, at the package's finest zoom
  std::string watermask;      // OGR polygons of water ("" = no water mask)
};

ExportSummary export_quantized_mesh(const MeshExportSettings& s, Progress& progress);

// --watermask: a water mask of polygons (256 x 256 bytes of a lon/lat box,
// web/mesh_tiles.hpp). Reading them needs GDAL: globe-tiler-gdal installs the
// factory (gdal_main.cpp), and globe-tiler hands exports with --watermask to
// it. Unset: --watermask is refused.
using WaterMask = std::function<std::vector<uint8_t>(double, double, double, double)>;
std::function<WaterMask(const std::string& path)>& water_mask_factory();

}  // namespace globe
