// globe-tiler: DEMs -> terrain packages, and tools to inspect them.
// The only place that turns errors into messages and exit codes (docs/cli.md).
#include <cstdio>
#include <string>
#include <vector>

#include "commands.hpp"
#include "error_report.hpp"
#include "errors.hpp"

namespace {

const char* kUsage =
    "usage: globe-tiler COMMAND [options]\n"
    "\n"
    "commands:\n"
    "  terrain INPUT... -o OUT.mbtiles   DEMs (any GDAL raster, any CRS) -> terrain package\n"
    "  info PACKAGE                      metadata, zoom range, tile counts and sizes\n"
    "  validate PACKAGE                  decode every tile, check schema and invariants\n"
    "  extract PACKAGE --zoom Z -o OUT.tif   decoded heights of one zoom as a GeoTIFF\n"
    "\n"
    "Run 'globe-tiler COMMAND --help' for the options of a command.\n"
    "Exit codes: 0 ok, 1 bad input data, 2 bad usage, 3 output cannot be written,\n"
    "            4 internal error, 5 validate found warnings only.\n";

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) {
    std::fputs(kUsage, stderr);
    return globe::kExitUsage;
  }
  const std::string command = args[0];
  args.erase(args.begin());
  std::string command_line = "globe-tiler";
  for (int i = 1; i < argc; ++i)
    command_line += std::string(" ") + argv[i];
  return globe::run_reporting_errors("globe-tiler", "globe-tiler " + command, "", [&]() -> int {
    if (command == "terrain") return globe::run_terrain(args, command_line);
    if (command == "info") return globe::run_info(args);
    if (command == "validate") return globe::run_validate(args);
    if (command == "extract") return globe::run_extract(args);
    if (command == "-h" || command == "--help" || command == "help") {
      std::fputs(kUsage, stdout);
      return globe::kExitOk;
    }
    if (command == "--version") {
      std::puts("globe-tiler " GLOBE_VERSION);
      return globe::kExitOk;
    }
    std::fprintf(stderr, "globe-tiler: unknown command '%s'\n\n%s", command.c_str(), kUsage);
    return globe::kExitUsage;
  });
}
