// `globe-tiler info PACKAGE`: metadata, zoom range, tile counts and sizes on
// stdout, for terrain and image packages.
#include <cstdio>

#include "commands.hpp"
#include "inspect_commands.hpp"
#include "package_info.hpp"
#include "runtime/cli_args.hpp"
#include "runtime/errors.hpp"
#include "runtime/image_package.hpp"
#include "runtime/package_open.hpp"
#include "runtime/terrain_package.hpp"
#include "tileformat/error.hpp"

namespace globe {

void print_image_info(const std::string& path) {
  ImagePackage p = open_image_package(path);
  print_package_info(*p.reader, path);
  uint64_t counts[3] = {0, 0, 0}, bad = 0;
  p.reader->for_each_tile([&](tileformat::TileId, std::span<const uint8_t> blob) {
    try {
      ++counts[static_cast<int>(tileformat::inspect_image_tile(blob).format)];
    } catch (const tileformat::FormatError&) {
      ++bad;
    }
  });
  std::printf("image: %d x %d px tiles, %s + alpha; tiles stored as png %llu, jpg %llu, webp %llu",
              p.tile_size, p.tile_size, p.colour == 1 ? "gray" : "RGB",
              static_cast<unsigned long long>(counts[0]),
              static_cast<unsigned long long>(counts[1]),
              static_cast<unsigned long long>(counts[2]));
  if (bad) std::printf(", not an image %llu (run validate)", static_cast<unsigned long long>(bad));
  std::printf("\n");
}

int run_info(const std::vector<std::string>& args) {
  CliArgs cli("globe-tiler info",
              "globe-tiler info PACKAGE\n\nPrints a terrain or image package's metadata, zoom "
              "range, tile counts and sizes.");
  auto positional = cli.parse_command(args, 1, 1, "PACKAGE");
  if (!positional) return kExitOk;
  const std::string& path = (*positional)[0];
  const auto kind = package_kind(path);
  if (kind == tileformat::PackageKind::kImage) {
    print_image_info(path);
    return kExitOk;
  }
  if (kind == tileformat::PackageKind::kAnalysis) {
    print_analysis_info(path);
    return kExitOk;
  }
  TerrainPackage p = open_terrain_package(path);
  print_package_info(*p.reader, path);
  return kExitOk;
}

}  // namespace globe
