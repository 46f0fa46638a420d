// `globe-vectorize areas`: parses options into AreasSettings, builds, and
// prints the summary.
#include <sstream>

#include "areas/areas_builder.hpp"
#include "areas/choropleth.hpp"
#include "kit/shard_plan.hpp"
#include "labels/label_options.hpp"
#include "lines/lines_options.hpp"
#include "runtime/cli_args.hpp"
#include "runtime/errors.hpp"
#include "vectorize_commands.hpp"

namespace globe {
namespace {

// The ramps' names, sequential then diverging, wrapped for --help.
std::string ramp_list() {
  std::string out;
  size_t line = 0;
  for (const ColorRamp& r : color_ramps()) {
    if (line > 60) {
      out += "\n                              ";
      line = 0;
    }
    out += (line ? " " : "") + std::string(r.name);
    line += std::string(r.name).size() + 1;
  }
  return out;
}

ChoroplethSettings& choropleth(AreasSettings& s) {
  if (!s.choropleth) s.choropleth.emplace();
  return *s.choropleth;
}

}  // namespace

int run_areas(const std::vector<std::string>& args) {
  AreasSettings s;
  CliArgs cli("globe-vectorize areas",
              "globe-vectorize areas INPUT... -o OUT.mbtiles [options]\n\n"
              "Turns polygons and multipolygons from any OGR source (Shapefile, GeoPackage,\n"
              "GeoJSON, FlatGeobuf, ...; any CRS, with holes) into an area package: per tile,\n"
              "the polygons clipped to the tile, snapped to the zoom's grid so that neighbours\n"
              "keep sharing their borders (docs/areas.md). Invalid polygons are repaired (GEOS\n"
              "MakeValid) and counted. With --choropleth, features are classed by a value.");
  declare_area_options(cli, s, "CRS of the inputs, for files without one (shapefile without .prj)",
                       "finest zoom (default: where the median edge spans 4 px, at most 18)");
  cli.option("--like", "PACKAGE",
             "use the tiling of this package (e.g. a local terrain), so tile ids match",
             [&](const std::string& v) { s.like = v; });
  cli.option("--layer", "NAME", "only this layer (repeatable; default: every layer)",
             [&](const std::string& v) { s.layers.push_back(v); });
  cli.option("--where", "SQL", "OGR attribute filter, e.g. \"pop > 1000000\"",
             [&](const std::string& v) { s.where = v; });
  cli.option("--class-field", "FIELD", "attribute whose value is the style class (default: layer)",
             [&](const std::string& v) { s.class_field = v; });
  cli.option("--class-map", "V=NAME,...", "rename class values, e.g. 1=water,2=forest",
             [&](const std::string& v) { s.class_map = v; });
  cli.option("--style", "CLASS:K=V,...",
             "a class's fill and outline (repeatable): color=#rrggbb, opacity=0.6,\n"
             "                              casing=#rrggbb@1px (the outline)",
             [&](const std::string& v) { s.styles.push_back(v); });
  cli.option("--choropleth", "FIELD[/DENOMINATOR]",
             "class features by a numeric field, or by field / denominator (a rate, e.g.\n"
             "                              pop/area_km2); features without a value are no-data",
             [&](const std::string& v) {
               ChoroplethSettings& c = choropleth(s);
               const auto slash = v.find('/');
               c.field = v.substr(0, slash);
               c.denominator = slash == std::string::npos ? "" : v.substr(slash + 1);
               if (c.field.empty() || (slash != std::string::npos && c.denominator.empty()))
                 throw UsageError("--choropleth takes FIELD or FIELD/DENOMINATOR, got '" + v + "'");
             });
  cli.option("--classes", "N", "choropleth classes (default 5; 2..12)", [&](const std::string& v) {
    choropleth(s).classes = CliArgs::to_int("--classes", v, 2, 12);
  });
  cli.option("--method", "M",
             "choropleth breaks: quantile (default), equal, jenks (natural breaks) or pretty\n"
             "                              (round numbers, as R's pretty)",
             [&](const std::string& v) {
               const auto m = parse_class_method(v);
               if (!m) throw UsageError("--method " + v + ": use quantile, equal, jenks or pretty");
               choropleth(s).method = *m;
             });
  cli.option("--colors", "RAMP", "ColorBrewer ramp of the classes (default YlOrRd): " + ramp_list(),
             [&](const std::string& v) { choropleth(s).colors = v; });
  cli.option("--no-data-color", "#RRGGBB", "colour of features without a value (default #cccccc)",
             [&](const std::string& v) {
               if (v.size() != 7 || v[0] != '#' ||
                   v.find_first_not_of("0123456789abcdefABCDEF", 1) != std::string::npos)
                 throw UsageError("--no-data-color takes #rrggbb, got '" + v + "'");
               choropleth(s).no_data_color = v;
             });
  declare_label_options(cli, s.labels, "a polygon (placed at its pole of inaccessibility)");
  cli.option("--simplify", "PX",
             "the snapping grid of each zoom but the finest, in pixels (default 0.5)",
             [&](const std::string& v) {
               s.simplify_px = CliArgs::to_double("--simplify", v);
               if (s.simplify_px < 0 || s.simplify_px > 16)
                 throw UsageError("--simplify must be within 0..16 pixels");
             });
  cli.option("--buffer", "PX", "how far polygons reach past a tile's edge (default 4 px)",
             [&](const std::string& v) { s.buffer_px = CliArgs::to_int("--buffer", v, 0, 64); });
  cli.option("--memory-mb", "MB",
             "memory for sorting tile pieces before spilling to disk (default 256)",
             [&](const std::string& v) {
               s.memory_mb = static_cast<size_t>(CliArgs::to_int("--memory-mb", v, 1, 1 << 20));
             });
  declare_shard_options(cli, s);
  declare_run_options(cli, s);
  if (!parse_build_command(cli, s, args, "globe-vectorize areas", "input vector file (see --help)"))
    return kExitOk;
  if (s.choropleth && s.choropleth->field.empty())
    throw UsageError("--classes, --method, --colors and --no-data-color need --choropleth FIELD");
  if (s.choropleth) {
    const ChoroplethSettings& c = *s.choropleth;
    if (!ramp_colors(c.colors, 3))
      throw UsageError("--colors " + c.colors + ": not a ColorBrewer ramp; use one of " +
                       ramp_list());
    if (!ramp_colors(c.colors, c.classes))
      throw UsageError("--colors " + c.colors + " has no ramp of " + std::to_string(c.classes) +
                       " classes (sequential ramps 3..9, diverging 3..11)");
    if (!s.class_field.empty())
      throw UsageError("--choropleth and --class-field both set the classes; use one");
  }
  if (!s.like.empty() && (s.tiling != tileformat::Scheme::kWebMercator || !s.t_srs.empty()))
    throw UsageError("--like takes the tiling from the package; drop --tiling/--t_srs");

  Progress progress(s.progress);
  const AreasSummary sum = build_areas(s, progress);
  std::ostringstream o;
  o.precision(3);
  o << std::fixed << "globe-vectorize: wrote " << s.output << ": " << sum.features_kept
    << " features (" << sum.features_skipped << " skipped, " << sum.repaired
    << " repaired by MakeValid, " << sum.bad_rings << " invalid or degenerate rings";
  if (sum.antimeridian_cuts) o << ", " << sum.antimeridian_cuts << " cut at the antimeridian";
  o << "), zoom " << sum.min_zoom << ".." << sum.max_zoom << ", " << sum.tiles << " tiles ("
    << sum.unique_blobs << " unique), " << sum.polygons << " polygons, " << sum.vertices
    << " vertices (" << sum.max_zoom_vertices << " at zoom " << sum.max_zoom << "), "
    << sum.dropped_small << " polygons below a zoom's grid left out there";
  if (s.choropleth) o << ", " << sum.no_data << " features without a value";
  o << ", " << sum.file_bytes << " bytes, " << sum.seconds << " s";
  if (sum.spilled_runs)
    o << "; sorted on disk in " << sum.spilled_runs << " runs (" << sum.spilled_bytes << " bytes)";
  progress.note(o.str());
  return kExitOk;
}

}  // namespace globe
