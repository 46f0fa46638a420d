// `globe-vectorize points`: parses options into PointsSettings, builds, and
// prints the summary.
#include <sstream>

#include "points/points_builder.hpp"
#include "runtime/cli_args.hpp"
#include "runtime/errors.hpp"
#include "vectorize_commands.hpp"

namespace globe {
int run_points(const std::vector<std::string>& args) {
  PointsSettings s;
  CliArgs cli("globe-vectorize points",
              "globe-vectorize points INPUT... -o OUT.mbtiles --fields A,B,... [options]\n\n"
              "Turns places with several numeric values (any OGR point layer, or a CSV file\n"
              "with coordinate columns, --xy) into a point package the viewer draws pie, bar\n"
              "and column charts from (docs/points.md). At coarser zooms, places closer than\n"
              "--merge-px pixels become one chart (their sums, or means), so a continental\n"
              "view shows regional charts and zooming in splits them.");
  declare_area_options(cli, s, "CRS of the inputs (default: theirs; with --xy, lon/lat)",
                       "finest zoom (default: where at most 1 % of the places have a neighbour "
                       "within --merge-px or tiles hold under 2 places, at most 16)");
  cli.option("--fields", "A,B,...", "the numeric fields a chart shows, in order (1 to 64)",
             [&](const std::string& v) {
               s.fields = CliArgs::to_names("--fields", v);
               if (s.fields.size() > 64) throw UsageError("--fields: at most 64 fields");
             });
  cli.option("--xy", "XCOL,YCOL",
             "read CSV files, points from these columns (longitude, latitude unless --s_srs)",
             [&](const std::string& v) {
               const std::vector<std::string> names = CliArgs::to_names("--xy", v, 2);
               s.xy = std::pair(names[0], names[1]);
             });
  cli.option("--label-field", "FIELD",
             "attribute that names a place: shown when picked, and stored as its label for\n"
             "                              globe-view and the MVT exports (docs/labels.md)",
             [&](const std::string& v) { s.label_field = v; });
  cli.option("--priority-field", "FIELD",
             "numeric attribute ranking the labels, larger first (default: the sum of --fields)",
             [&](const std::string& v) { s.priority_field = v; });
  cli.option("--like", "PACKAGE",
             "use the tiling of this package (e.g. a local terrain), so tile ids match",
             [&](const std::string& v) { s.like = v; });
  cli.option("--layer", "NAME", "only this layer (repeatable; default: every layer)",
             [&](const std::string& v) { s.layers.push_back(v); });
  cli.option("--where", "SQL", "OGR attribute filter, e.g. \"total > 100\"",
             [&](const std::string& v) { s.where = v; });
  cli.option("--aggregate", "sum|mean",
             "what a merged place shows: the sums of its places' values (default) or their "
             "means",
             [&](const std::string& v) {
               if (v != "sum" && v != "mean")
                 throw UsageError("--aggregate: '" + v + "' is not sum or mean");
               s.aggregate = v == "sum" ? tileformat::PointAggregate::kSum
                                        : tileformat::PointAggregate::kMean;
             });
  cli.option("--merge-px", "PX",
             "places closer than this many pixels at a zoom become one (default 40; 0 = only "
             "places at the same position)",
             [&](const std::string& v) {
               s.merge_px = CliArgs::to_double("--merge-px", v);
               if (s.merge_px < 0 || s.merge_px > 1024)
                 throw UsageError("--merge-px must be within 0..1024 pixels");
             });
  cli.option("--chart-max-px", "PX",
             "largest chart size (pixels at 256 px per tile) the cluster grids allow for "
             "(default 48)",
             [&](const std::string& v) {
               s.chart_max_px = CliArgs::to_double("--chart-max-px", v);
               if (s.chart_max_px < 1 || s.chart_max_px > 512)
                 throw UsageError("--chart-max-px must be within 1..512 pixels");
             });
  cli.flag("--signed",
           "keep negative values (the package is then for bar and column charts; pies and "
           "stacked bars need shares)",
           [&] { s.sign = ValueSign::kSigned; });
  cli.option("--cluster-grid", "C", "cluster cells per tile side (default 16)",
             [&](const std::string& v) {
               s.cluster_grid = CliArgs::to_int("--cluster-grid", v, 1, 256);
               if (4096 % s.cluster_grid != 0)
                 throw UsageError("--cluster-grid must divide 4096 (1, 2, 4, ... 256)");
             });
  cli.option("--memory-mb", "MB",
             "memory for sorting places before spilling to disk (default 64); the places "
             "themselves are never all held",
             [&](const std::string& v) {
               s.memory_mb = static_cast<size_t>(CliArgs::to_int("--memory-mb", v, 1, 1 << 20));
             });
  declare_run_options(cli, s);
  if (!parse_build_command(cli, s, args, "globe-vectorize points",
                           "input vector file (see --help)"))
    return kExitOk;
  if (s.fields.empty())
    throw UsageError(
        "--fields is required: the numeric fields each chart shows, e.g. --fields "
        "a,b,c");
  if (!s.like.empty() && (s.tiling != tileformat::Scheme::kWebMercator || !s.t_srs.empty()))
    throw UsageError("--like takes the tiling from the package; drop --tiling/--t_srs");
  // Zero merges only places at the same position: a tiny radius.
  if (s.merge_px == 0) s.merge_px = 1e-9;

  Progress progress(s.progress);
  const PointsSummary sum = build_points(s, progress);
  std::ostringstream o;
  o.precision(3);
  o << std::fixed << "globe-vectorize: wrote " << s.output << ": " << sum.places << " places ("
    << sum.features_read << " features read; skipped: " << sum.skipped_no_point
    << " without a point, " << sum.skipped_unprojected << " not transformable, "
    << sum.skipped_outside << " outside --bbox; " << sum.empty_values
    << " empty values read as 0), zoom " << sum.min_zoom << ".." << sum.max_zoom << " ("
    << sum.coarsest_places << " charts at zoom " << sum.min_zoom << "), " << sum.tiles << " tiles ("
    << sum.unique_blobs << " unique), " << sum.file_bytes << " bytes, " << sum.seconds
    << " s; merging held at most " << sum.peak_merge_places << " places";
  progress.note(o.str());
  return kExitOk;
}

}  // namespace globe
