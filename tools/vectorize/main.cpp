// globe-vectorize: vector data (any OGR source) -> line-cluster packages, and
// tools to inspect them. Errors become messages and exit codes in one place
// (tools/common/error_report, docs/cli.md).
#include <cstdio>
#include <string>
#include <vector>

#include "commands.hpp"
#include "error_report.hpp"
#include "errors.hpp"

namespace {

const char* kUsage =
    "usage: globe-vectorize COMMAND [options]\n"
    "\n"
    "commands:\n"
    "  lines INPUT... -o OUT.mbtiles      lines, polygon outlines and points (Shapefile,\n"
    "                                     GeoPackage, GeoJSON, OSM, ...) -> line-cluster package\n"
    "  info PACKAGE                       metadata, classes, zoom range, tiles and segments\n"
    "  validate PACKAGE                   decode every tile, recheck every cluster grid\n"
    "  extract PACKAGE --zoom Z -o OUT.gpkg   decoded lines of one zoom as vector data\n"
    "\n"
    "Run 'globe-vectorize COMMAND --help' for the options of a command.\n"
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
  return globe::run_reporting_errors(
      "globe-vectorize", "globe-vectorize " + command, "", [&]() -> int {
        if (command == "lines") return globe::run_lines(args);
        if (command == "info") return globe::run_lines_info(args);
        if (command == "validate") return globe::run_lines_validate(args);
        if (command == "extract") return globe::run_lines_extract(args);
        if (command == "-h" || command == "--help" || command == "help") {
          std::fputs(kUsage, stdout);
          return globe::kExitOk;
        }
        if (command == "--version") {
          std::puts("globe-vectorize " GLOBE_VERSION);
          return globe::kExitOk;
        }
        std::fprintf(stderr, "globe-vectorize: unknown command '%s'\n\n%s", command.c_str(),
                     kUsage);
        return globe::kExitUsage;
      });
}
