// What both globe-tiler executables share before dispatching: the usage
// text and the allocator settings.
#include <malloc.h>

#include "commands.hpp"

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
    "\n"
    "Run 'globe-tiler COMMAND --help' for the options of a command.\n"
    "Exit codes: 0 ok, 1 bad input data, 2 bad usage, 3 output cannot be written,\n"
    "            4 internal error, 5 validate found warnings only.\n";

void tune_tiler_malloc() {
  // The builders' working buffers (blocks of 257^2 samples, warp windows)
  // are a few hundred KiB each, allocated and freed per tile: served from
  // mmap by default, every one of them page-faults afresh. Kept in the heap
  // (and the heap not trimmed after each), they are reused.
  mallopt(M_MMAP_THRESHOLD, 64 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
}

}  // namespace globe
