// `globe-tiler info PACKAGE`: metadata, zoom range, tile counts and sizes on stdout.
#include "cli_args.hpp"
#include "commands.hpp"
#include "errors.hpp"
#include "package_info.hpp"
#include "terrain_package.hpp"

namespace globe {

int run_info(const std::vector<std::string>& args) {
  CliArgs cli("globe-tiler info",
              "globe-tiler info PACKAGE\n\nPrints a package's metadata, zoom range, tile counts "
              "and sizes.");
  auto positional = cli.parse_command(args, 1, 1, "PACKAGE");
  if (!positional) return kExitOk;
  const std::string& path = (*positional)[0];
  TerrainPackage p = open_terrain_package(path);
  print_package_info(*p.reader, path);
  return kExitOk;
}

}  // namespace globe
