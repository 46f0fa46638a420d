// `globe-vectorize lines`: parses options into LinesSettings, builds, and
// prints the summary.
#include <sstream>

#include "labels/label_options.hpp"
#include "lines/lines_builder.hpp"
#include "lines/lines_options.hpp"
#include "runtime/cli_args.hpp"
#include "runtime/errors.hpp"
#include "vectorize_commands.hpp"

namespace globe {

int run_lines(const std::vector<std::string>& args) {
  LinesSettings s;
  CliArgs cli("globe-vectorize lines",
              "globe-vectorize lines INPUT... -o OUT.mbtiles [options]\n\n"
              "Turns lines, polygon outlines and points from any OGR source (Shapefile,\n"
              "GeoPackage, GeoJSON, TopoJSON, OSM, ...; several inputs and layers form one\n"
              "package) into line-cluster tiles: per tile, simplified segments and a cluster\n"
              "grid the viewer shades lines from (docs/lines.md).");
  declare_area_options(cli, s, "CRS of the inputs, for files without one (shapefile without .prj)",
                       "finest zoom (default: where the median segment spans 4 px, at most 18)");
  cli.option("--like", "PACKAGE",
             "use the tiling of this package (e.g. a local terrain), so tile ids match",
             [&](const std::string& v) { s.like = v; });
  cli.option("--layer", "NAME", "only this layer (repeatable; default: every layer)",
             [&](const std::string& v) { s.layers.push_back(v); });
  cli.option("--where", "SQL", "OGR attribute filter, e.g. \"CLASS <= 2\"",
             [&](const std::string& v) { s.where = v; });
  cli.option("--class-field", "FIELD", "attribute whose value is the style class (default: layer)",
             [&](const std::string& v) { s.class_field = v; });
  cli.option("--class-map", "V=NAME,...", "rename class values, e.g. 1=highway,2=primary",
             [&](const std::string& v) { s.class_map = v; });
  declare_line_tile_options(cli, s);
  declare_label_options(cli, s.labels, "a line (drawn along it: rivers, roads, airways)");
  declare_shard_options(cli, s);
  declare_run_options(cli, s);
  if (!parse_build_command(cli, s, args, "globe-vectorize lines", "input vector file (see --help)"))
    return kExitOk;
  if (!s.like.empty() && (s.tiling != tileformat::Scheme::kWebMercator || !s.t_srs.empty()))
    throw UsageError("--like takes the tiling from the package; drop --tiling/--t_srs");

  Progress progress(s.progress);
  const LinesSummary sum = build_lines(s, progress);
  std::ostringstream o;
  o.precision(3);
  o << std::fixed << "globe-vectorize: wrote " << s.output << ": " << sum.features_kept
    << " features (" << sum.features_skipped << " skipped, " << sum.bad_parts
    << " invalid or degenerate parts";
  if (sum.antimeridian_cuts) o << ", " << sum.antimeridian_cuts << " antimeridian cuts";
  o << "), zoom " << sum.min_zoom << ".." << sum.max_zoom << ", " << sum.tiles << " tiles ("
    << sum.unique_blobs << " unique), " << sum.segments << " segments (" << sum.max_zoom_segments
    << " at zoom " << sum.max_zoom << "), " << sum.points << " points, " << sum.file_bytes
    << " bytes, " << sum.seconds << " s";
  if (sum.spilled_runs)
    o << "; sorted on disk in " << sum.spilled_runs << " runs (" << sum.spilled_bytes << " bytes)";
  progress.note(o.str());
  return kExitOk;
}

}  // namespace globe
