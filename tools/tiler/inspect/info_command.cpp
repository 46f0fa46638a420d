// `globe-tiler info PACKAGE`: metadata, zoom range, tile counts and sizes on
// stdout, for terrain and image packages.
#include <cstdio>

#include "inspect/inspect_commands.hpp"
#include "kit/package_info.hpp"
#include "runtime/cli_args.hpp"
#include "runtime/errors.hpp"
#include "runtime/image_package.hpp"
#include "runtime/package_open.hpp"
#include "runtime/terrain_package.hpp"
#include "tileformat/error.hpp"
#include "tiler_commands.hpp"

namespace globe {

void print_image_info(const std::string& path, bool json) {
  ImagePackage p = open_image_package(path);
  uint64_t counts[3] = {0, 0, 0}, bad = 0;
  p.reader->for_each_tile([&](tileformat::TileId, std::span<const uint8_t> blob) {
    try {
      ++counts[static_cast<int>(tileformat::inspect_image_tile(blob).format)];
    } catch (const tileformat::FormatError&) {
      ++bad;
    }
  });
  if (json) {
    InfoJson image;
    image.integer("tile_px", uint64_t(p.tile_size))
        .text("colour", p.colour == 1 ? "gray" : "rgb")
        .object("stored", InfoJson()
                              .integer("png", counts[0])
                              .integer("jpg", counts[1])
                              .integer("webp", counts[2]))
        .integer("not_images", bad);
    print_info_json(package_info_json(*p.reader, path, "image").object("image", image));
    return;
  }
  print_package_info(*p.reader, path);
  std::printf("image: %d x %d px tiles, %s + alpha; tiles stored as png %llu, jpg %llu, webp %llu",
              p.tile_size, p.tile_size, p.colour == 1 ? "gray" : "RGB",
              static_cast<unsigned long long>(counts[0]),
              static_cast<unsigned long long>(counts[1]),
              static_cast<unsigned long long>(counts[2]));
  if (bad) std::printf(", not an image %llu (run validate)", static_cast<unsigned long long>(bad));
  std::printf("\n");
}

int run_info(const std::vector<std::string>& args) {
  bool json = false;
  CliArgs cli("globe-tiler info",
              "globe-tiler info PACKAGE [--json]\n\nPrints a terrain, image or analysis "
              "package's metadata, zoom range, tile counts and sizes.");
  cli.flag("--json", "one JSON object on stdout instead (docs/cli.md \"info --json\")",
           [&] { json = true; });
  auto positional = cli.parse_command(args, 1, 1, "PACKAGE");
  if (!positional) return kExitOk;
  const std::string& path = (*positional)[0];
  const auto kind = package_kind(path);
  if (kind == tileformat::PackageKind::kImage) {
    print_image_info(path, json);
    return kExitOk;
  }
  if (kind == tileformat::PackageKind::kAnalysis) {
    print_analysis_info(path, json);
    return kExitOk;
  }
  TerrainPackage p = open_terrain_package(path);
  if (json) {
    InfoJson terrain;
    terrain.text("tiling", tileformat::scheme_name(p.tiling.scheme))
        .integer("block_size", uint64_t(p.block_size))
        .integer("kpatch_lattice", uint64_t(p.lattice))
        .number("height_step_m", p.step_m)
        .integer("min_zoom", uint64_t(p.min_zoom))
        .integer("max_zoom", uint64_t(p.max_zoom));
    print_info_json(package_info_json(*p.reader, path, "terrain").object("terrain", terrain));
    return kExitOk;
  }
  print_package_info(*p.reader, path);
  return kExitOk;
}

}  // namespace globe
