// `globe-vectorize info PACKAGE`: metadata, zoom table, and per zoom the
// segments, points and cluster-grid entries (from tile headers only).
#include <cstdio>
#include <map>

#include "inspect/points_inspect.hpp"
#include "kit/package_info.hpp"
#include "runtime/cli_args.hpp"
#include "runtime/errors.hpp"
#include "runtime/line_package.hpp"
#include "runtime/package_open.hpp"
#include "tileformat/feature_table.hpp"
#include "tileformat/json.hpp"
#include "tileformat/line_tile.hpp"
#include "vectorize_commands.hpp"

namespace globe {

namespace {

// A bundled-flow package's summary (metadata globe:bundle, tileformat §7.5).
// The parsed globe:bundle; throws InputError if it is not JSON.
tileformat::JsonValue bundle_json(const std::string& json, const std::string& path) {
  try {
    return tileformat::JsonValue::parse(json);
  } catch (const std::exception& e) {
    throw InputError(path + ": metadata globe:bundle is not JSON (" + e.what() +
                     "); rebuild the package (tileformat §7.5)");
  }
}

void print_bundle_info(const std::string& json, const std::string& path) {
  const tileformat::JsonValue b = bundle_json(json, path);
  auto num = [&](const char* key) {
    const tileformat::JsonValue* v = b.find(key);
    return v && v->is_number() ? v->number() : 0.0;
  };
  std::printf("bundled flows:\n");
  std::printf(
      "  connections %.0f: %.0f routed, %.0f unrouted (%.0f beyond --max-snap, %.0f on "
      "one node, %.0f across network components); %.0f bad rows\n",
      num("connections"), num("routed"), num("unrouted"), num("unsnapped"), num("same_node"),
      num("disconnected"), num("bad_rows"));
  std::printf("  bundles %.0f, straight lines %.0f\n", num("bundles"), num("straight_lines"));
  std::printf("  mean detour %.3f (path length / great-circle distance)\n", num("mean_detour"));
  std::printf("  ink ratio %.3f (drawn length / sum of straight lengths)\n", num("ink_ratio"));
  if (b.find("significance"))
    std::printf(
        "  significance %g of the heaviest flow in view: %.0f flows hidden at the coarsest "
        "zoom; --min-weight %g: %.0f never drawn\n",
        num("significance"), num("hidden_at_min_zoom"), num("min_weight"), num("never_drawn"));
  if (const tileformat::JsonValue* n = b.find("network"); n && n->is_object()) {
    auto nn = [&](const char* key) {
      const tileformat::JsonValue* v = n->find(key);
      return v && v->is_number() ? v->number() : 0.0;
    };
    std::printf(
        "  network %.0f nodes, %.0f edges, %.0f components; reduced to %.0f nodes, %.0f "
        "edges\n",
        nn("nodes"), nn("edges"), nn("components"), nn("reduced_nodes"), nn("reduced_edges"));
  }
  if (const tileformat::JsonValue* c = b.find("weight_classes"); c && c->is_array())
    for (const tileformat::JsonValue& k : c->array()) {
      const tileformat::JsonValue *name = k.find("class"), *lo = k.find("min"), *hi = k.find("max");
      if (name && name->is_string() && lo && lo->is_number() && hi && hi->is_number())
        std::printf("  %-10s weight %g .. %g\n", name->string().c_str(), lo->number(),
                    hi->number());
    }
}

}  // namespace

int run_lines_info(const std::vector<std::string>& args) {
  bool json = false;
  CliArgs cli("globe-vectorize info",
              "globe-vectorize info PACKAGE [--json]\n\nPrints a line package's metadata, "
              "classes, zoom range, tiles, segments and points; of a point package, its fields "
              "and places.");
  cli.flag("--json", "one JSON object on stdout instead (docs/cli.md \"info --json\")",
           [&] { json = true; });
  auto positional = cli.parse_command(args, 1, 1, "PACKAGE");
  if (!positional) return kExitOk;
  const std::string& path = (*positional)[0];
  if (package_kind(path) == tileformat::PackageKind::kPoints) return points_info(path, json);
  LinePackage p = open_line_package(path);
  std::map<int, tileformat::LineTileCounts> per_zoom;
  p.reader->for_each_tile([&](tileformat::TileId id, std::span<const uint8_t> blob) {
    const auto c = tileformat::peek_line_tile_counts(blob);
    auto& z = per_zoom[id.z];
    z.runs += c.runs;
    z.segments += c.segments;
    z.points += c.points;
    z.cell_entries += c.cell_entries;
  });
  const int64_t features = tileformat::FeatureTableReader(*p.reader).count();
  if (json) {
    std::vector<std::string> classes;
    for (const auto& c : p.classes)
      classes.push_back(c.name);
    std::vector<InfoJson> zooms;
    for (const auto& [z, c] : per_zoom)
      zooms.push_back(InfoJson()
                          .integer("zoom", uint64_t(z))
                          .integer("segments", c.segments)
                          .integer("runs", c.runs)
                          .integer("points", c.points)
                          .integer("cell_entries", c.cell_entries));
    InfoJson lines;
    lines.texts("classes", classes)
        .integer("features", uint64_t(features))
        .objects("per_zoom", zooms);
    if (!p.meta.bundle_json.empty()) {
      bundle_json(p.meta.bundle_json, path);  // checked: it is JSON
      lines.raw("bundle", p.meta.bundle_json);
    }
    print_info_json(package_info_json(*p.reader, path, "lines").object("lines", lines));
    return kExitOk;
  }
  print_package_info(*p.reader, path);
  std::printf("classes:\n");
  for (size_t i = 0; i < p.classes.size(); ++i)
    std::printf("  %4zu %s\n", i, p.classes[i].name.c_str());
  std::printf("features: %lld\n", static_cast<long long>(features));
  if (!p.meta.bundle_json.empty()) print_bundle_info(p.meta.bundle_json, path);
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
