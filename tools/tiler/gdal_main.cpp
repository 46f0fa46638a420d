// globe-tiler-gdal: every globe-tiler command, in a process that links GDAL.
// Users type `globe-tiler`, which runs `analyze` itself and execs this
// executable for the others (main.cpp). Dispatch and error reporting:
// tools/common/kit/command_tool.
#include <memory>

#include "export/mesh_export.hpp"
#include "geo/polygon_mask.hpp"
#include "kit/command_tool.hpp"
#include "kit/heap_tuning.hpp"
#include "tiler_commands.hpp"

int main(int argc, char** argv) {
  globe::keep_tile_buffers_in_heap();
  // Water masks for quantized-mesh exports are read with OGR, here.
  globe::water_mask_factory() = [](const std::string& path) -> globe::WaterMask {
    auto mask = std::make_shared<globe::PolygonMask>(path);
    return
        [mask](double w, double s, double e, double n) { return mask->rasterize(w, s, e, n, 256); };
  };
  return globe::run_command_tool("globe-tiler", GLOBE_VERSION, globe::kTilerUsage,
                                 {{"terrain", globe::run_terrain},
                                  {"imagery", globe::run_imagery},
                                  {"analyze", globe::run_analyze},
                                  {"merge", globe::run_merge},
                                  {"info", globe::run_info},
                                  {"validate", globe::run_validate},
                                  {"extract", globe::run_extract},
                                  {"export", globe::run_export}},
                                 argc, argv);
}
