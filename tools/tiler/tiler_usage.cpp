// What both globe-tiler executables share before dispatching: the usage
// text.
#include "tiler_commands.hpp"

namespace globe {

const char* const kTilerUsage =
    "usage: globe-tiler COMMAND [options]\n"
    "\n"
    "commands:\n"
    "  terrain INPUT... -o OUT.mbtiles   DEMs (any GDAL raster, any CRS) -> terrain package\n"
    "  imagery INPUT... -o OUT.mbtiles   images (any GDAL raster, any CRS) -> image package\n"
    "  analyze TERRAIN -o OUT.mbtiles    slope, aspect, curvature, sky view, flow -> analysis\n"
    "  merge SHARD... -o OUT.mbtiles     shards of a --shard I/N build -> one package\n"
    "  info PACKAGE                      metadata, zoom range, tile counts and sizes\n"
    "  validate PACKAGE                  decode every tile, check schema and invariants\n"
    "  extract PACKAGE --zoom Z -o OUT.tif   one zoom as a GeoTIFF (heights, pixels or a layer)\n"
    "  export PACKAGE -o OUT.pmtiles     web formats: Terrarium/Terrain-RGB, quantized-mesh,\n"
    "                                    image tiles\n"
    "\n"
    "Run 'globe-tiler COMMAND --help' for the options of a command.\n"
    "Exit codes: 0 ok, 1 bad input data, 2 bad usage, 3 output cannot be written,\n"
    "            4 internal error, 5 validate found warnings only.\n";

}  // namespace globe
