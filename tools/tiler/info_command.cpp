// `globe-tiler info PACKAGE`: metadata, zoom range, tile counts and sizes on stdout.
#include <cstdio>
#include <filesystem>

#include "cli_args.hpp"
#include "commands.hpp"
#include "errors.hpp"
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
  std::printf("package: %s\n", path.c_str());
  std::error_code ec;
  std::printf("file size: %llu bytes\n",
              static_cast<unsigned long long>(std::filesystem::file_size(path, ec)));
  std::printf("metadata:\n");
  for (const auto& [k, v] : p.reader->metadata()) {
    std::string value = v;
    if (k == "globe:crs" && value.size() > 80) value = value.substr(0, 77) + "...";
    std::printf("  %-22s %s\n", k.c_str(), value.c_str());
  }
  std::printf("zoom levels:\n  %4s %10s %14s %12s  %s\n", "zoom", "tiles", "bytes", "bytes/tile",
              "x range, y range");
  uint64_t tiles = 0, bytes = 0;
  for (const auto& z : p.reader->zoom_summaries()) {
    std::printf("  %4d %10llu %14llu %12llu  x %u..%u, y %u..%u\n", z.zoom,
                static_cast<unsigned long long>(z.tiles), static_cast<unsigned long long>(z.bytes),
                static_cast<unsigned long long>(z.tiles ? z.bytes / z.tiles : 0), z.min_x, z.max_x,
                z.min_y, z.max_y);
    tiles += z.tiles;
    bytes += z.bytes;
  }
  std::printf("total: %llu tiles, %llu unique blobs, %llu tile bytes\n",
              static_cast<unsigned long long>(tiles),
              static_cast<unsigned long long>(p.reader->unique_blobs()),
              static_cast<unsigned long long>(bytes));
  return kExitOk;
}

}  // namespace globe
