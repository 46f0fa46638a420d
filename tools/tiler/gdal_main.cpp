// globe-tiler-gdal: every globe-tiler command, in a process that links GDAL.
// Users type `globe-tiler`, which runs `analyze` itself and execs this
// executable for the others (main.cpp). Dispatch and error reporting:
// tools/common/kit/command_tool.
#include "command_tool.hpp"
#include "commands.hpp"
#include "heap_tuning.hpp"

int main(int argc, char** argv) {
  globe::keep_tile_buffers_in_heap();
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
