// `globe-vectorize info PACKAGE`: metadata, zoom table, and per zoom the
// segments, points and cluster-grid entries (from tile headers only).
#include <cstdio>
#include <map>

#include "cli_args.hpp"
#include "commands.hpp"
#include "errors.hpp"
#include "line_package.hpp"
#include "package_info.hpp"
#include "package_open.hpp"
#include "points_inspect.hpp"
#include "tileformat/feature_table.hpp"
#include "tileformat/line_tile.hpp"

namespace globe {

int run_lines_info(const std::vector<std::string>& args) {
  CliArgs cli("globe-vectorize info",
              "globe-vectorize info PACKAGE\n\nPrints a line package's metadata, classes, zoom "
              "range, tiles, segments and points; of a point package, its fields and places.");
  auto positional = cli.parse_command(args, 1, 1, "PACKAGE");
  if (!positional) return kExitOk;
  const std::string& path = (*positional)[0];
  if (package_kind(path) == tileformat::PackageKind::kPoints) return points_info(path);
  LinePackage p = open_line_package(path);
  print_package_info(*p.reader, path);
  std::printf("classes:\n");
  for (size_t i = 0; i < p.classes.size(); ++i)
    std::printf("  %4zu %s\n", i, p.classes[i].name.c_str());
  std::printf("features: %lld\n",
              static_cast<long long>(tileformat::FeatureTableReader(*p.reader).count()));
  std::map<int, tileformat::LineTileCounts> per_zoom;
  p.reader->for_each_tile([&](tileformat::TileId id, std::span<const uint8_t> blob) {
    const auto c = tileformat::peek_line_tile_counts(blob);
    auto& z = per_zoom[id.z];
    z.runs += c.runs;
    z.segments += c.segments;
    z.points += c.points;
    z.cell_entries += c.cell_entries;
  });
  std::printf("lines per zoom:\n  %4s %12s %12s %10s %14s %10s\n", "zoom", "segments", "runs",
              "points", "cell entries", "per cell");
  const double cells = double(p.cluster_grid) * p.cluster_grid;
  std::map<int, uint64_t> tiles;
  for (const tileformat::ZoomSummary& s : p.reader->zoom_summaries())
    tiles[s.zoom] = s.tiles;
  for (const auto& [z, c] : per_zoom)
    std::printf("  %4d %12u %12u %10u %14u %10.2f\n", z, c.segments, c.runs, c.points,
                c.cell_entries, c.cell_entries / (cells * double(tiles[z])));
  return kExitOk;
}

}  // namespace globe
