// `globe-vectorize validate PACKAGE`: decodes every tile (every §7 check of
// the decoder) and checks the package invariants (docs/tileformat.md §7):
//   - extent and grid match the metadata; one reach per zoom;
//   - the cluster grid equals the one recomputed from the segments (§7.3):
//     no segment missing from a cell its footprint touches, none listed in a
//     cell it misses;
//   - every feature id exists in the features table, every class id in
//     globe:classes; tiles lie within minzoom..maxzoom.
// Report on stdout. Exit 0 valid, 5 warnings only, 1 errors.
#include <cstdio>
#include <map>

#include "inspect/points_inspect.hpp"
#include "kit/validation_report.hpp"
#include "runtime/cli_args.hpp"
#include "runtime/errors.hpp"
#include "runtime/line_package.hpp"
#include "runtime/package_open.hpp"
#include "tileformat/error.hpp"
#include "tileformat/feature_table.hpp"
#include "tileformat/line_clusters.hpp"
#include "tileformat/line_tile.hpp"
#include "tileformat/shard_table.hpp"
#include "vectorize_commands.hpp"

namespace globe {
int run_lines_validate(const std::vector<std::string>& args) {
  CliArgs cli("globe-vectorize validate",
              "globe-vectorize validate PACKAGE\n\nDecodes every tile, recomputes every cluster "
              "grid and checks feature and class ids.\nExit 0 valid, 5 warnings only, 1 errors.");
  auto positional = cli.parse_command(args, 1, 1, "PACKAGE");
  if (!positional) return kExitOk;
  const std::string& path = (*positional)[0];
  if (package_kind(path) == tileformat::PackageKind::kPoints) return points_validate(path);
  LinePackage p = open_line_package(path);
  ValidationReport r;
  tileformat::FeatureTableReader features(*p.reader);
  const int64_t max_id = features.max_id();
  const int64_t count = features.count();
  // A shard of a sharded build but shard 0 has an empty features table
  // (shard 0 holds it, docs/tileformat.md §10): its tiles' ids are not checked.
  const auto shard =
      read_metadata(path, [&] { return tileformat::read_shard_metadata(p.reader->metadata()); });
  const bool features_in_shard_0 = shard && shard->index != 0 && count == 0;
  if (features_in_shard_0)
    std::printf("%s: shard %d/%d: its features are in shard 0's features table\n", path.c_str(),
                shard->index, shard->count);
  if (count != max_id)
    r.warning("features table ids are not 1.." + std::to_string(count) + " (max id " +
              std::to_string(max_id) + ")");
  std::map<int, uint32_t> reach;
  uint64_t tiles = 0, segments = 0;
  p.reader->for_each_tile([&](tileformat::TileId id, std::span<const uint8_t> blob) {
    ++tiles;
    const std::string where = path + " tile " + id.str();
    tileformat::LineTile t;
    try {
      t = tileformat::decode_line_tile(blob);
    } catch (const tileformat::FormatError& e) {
      r.error(where + ": " + e.what());
      return;
    }
    segments += t.segment_count();
    if (id.z < p.min_zoom || id.z > p.max_zoom)
      r.warning(where + ": outside the metadata zoom range " + std::to_string(p.min_zoom) + ".." +
                std::to_string(p.max_zoom));
    if (int(t.extent) != p.extent || int(t.grid) != p.cluster_grid)
      r.error(where + ": extent/grid " + std::to_string(t.extent) + "/" + std::to_string(t.grid) +
              " differ from the metadata (tileformat §7.1)");
    if (auto [it, fresh] = reach.emplace(id.z, t.reach); !fresh && it->second != t.reach)
      r.warning(where + ": reach " + std::to_string(t.reach) +
                " differs from other tiles of zoom " + std::to_string(id.z));
    for (uint64_t f : t.feature_ids)
      if (!features_in_shard_0 && (f < 1 || int64_t(f) > max_id)) {
        r.error(where + ": feature id " + std::to_string(f) + " not in the features table");
        break;
      }
    for (const auto& run : t.runs)
      if (run.class_id >= p.classes.size()) {
        r.error(where + ": class id " + std::to_string(run.class_id) + " not in globe:classes");
        break;
      }
    tileformat::LineTile again = t;
    tileformat::build_cluster_grid(again);
    if (again.cell_offsets != t.cell_offsets || again.cell_segments != t.cell_segments) {
      for (size_t c = 0; c + 1 < t.cell_offsets.size(); ++c) {
        const auto n0 = t.cell_offsets[c + 1] - t.cell_offsets[c];
        const auto n1 = again.cell_offsets[c + 1] - again.cell_offsets[c];
        if (n0 != n1 || !std::equal(t.cell_segments.begin() + t.cell_offsets[c],
                                    t.cell_segments.begin() + t.cell_offsets[c + 1],
                                    again.cell_segments.begin() + again.cell_offsets[c])) {
          r.error(where + ": cluster cell " + std::to_string(c) + " lists " + std::to_string(n0) +
                  " segments, the footprint rule gives " + std::to_string(n1) +
                  " (tileformat §7.3)");
          break;
        }
      }
    }
  });
  std::printf("%s: %llu tiles, %llu segments, %lld features: %llu errors, %llu warnings\n",
              path.c_str(), static_cast<unsigned long long>(tiles),
              static_cast<unsigned long long>(segments), static_cast<long long>(count),
              static_cast<unsigned long long>(r.errors),
              static_cast<unsigned long long>(r.warnings));
  return r.exit_code();
}

}  // namespace globe
