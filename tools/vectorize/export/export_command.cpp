// `globe-vectorize export PACKAGE --format mvt -o OUT [--style-json STYLE.json]`:
// line, bundle, point and area packages as vector tiles for web maps (docs/web.md).
#include <sstream>

#include "export/area_mvt_export.hpp"
#include "export/mvt_export.hpp"
#include "export/point_mvt_export.hpp"
#include "kit/build_options.hpp"
#include "runtime/cli_args.hpp"
#include "runtime/errors.hpp"
#include "runtime/package_open.hpp"
#include "vectorize_commands.hpp"

namespace globe {

int run_export(const std::vector<std::string>& args) {
  BuildOptions o;
  MvtExportSettings s;
  std::string format = "mvt";
  CliArgs cli(
      "globe-vectorize export",
      "globe-vectorize export PACKAGE --format mvt -o OUT.pmtiles|OUT.mbtiles|DIR\n"
      "                       [--style-json STYLE.json] [--glyphs DIR]\n\n"
      "Converts a line or bundle package (web mercator) to Mapbox Vector Tiles 2.1 for web\n"
      "maps (MapLibre GL, OpenLayers, QGIS): one MVT layer per layer of the package's\n"
      "features table (e.g. roads, bundles, unrouted), each line with its feature id, its\n"
      "class ('class') and its attributes (bundles: weight, count, ...); tiles gzipped, into\n"
      "one PMTiles file, an MBTiles file or a folder DIR/{z}/{x}/{y}.pbf with metadata.json.\n"
      "--style-json writes a MapLibre style that draws the classes with the package's colours,\n"
      "widths, dashes, casings and opacities. Lines of zero length, which MVT cannot hold,\n"
      "become points tagged zero_length. A point package becomes one layer 'points': each\n"
      "place a point with its id, 'count' (the source places it stands for) and its fields\n"
      "(sums or means, as the package aggregates); its style draws circles sized by count.\n"
      "An area package becomes one layer per source layer, each feature's polygons in a tile\n"
      "one (multi)polygon with its id, 'class', attributes and, in a choropleth, 'value'; its\n"
      "style fills the classes (a choropleth as a step over 'value') under outlines, and a\n"
      "point layer 'labels' holds one point per labelled area at its label's anchor.\n"
      "A package built with --label-field gives its labels as 'name'; its style writes them\n"
      "(symbol layers) with glyph PBFs written into 'fonts' beside the style (--glyphs).\n"
      "docs/web.md has a MapLibre page.");
  cli.option("--format", "mvt", "vector tiles (the only format, the default)",
             [&](const std::string& v) {
               if (v != "mvt") throw UsageError("--format: '" + v + "' is not mvt");
               format = v;
             });
  cli.option("--style-json", "STYLE.json", "also write a MapLibre style (version 8) for the tiles",
             [&](const std::string& v) { s.style_json = v; });
  cli.option("--glyphs", "DIR",
             "write the labels' MapLibre glyph PBFs into DIR/{fontstack}/{range}.pbf\n"
             "                              (default: 'fonts' beside --style-json, for a package "
             "with labels)",
             [&](const std::string& v) { s.glyphs_dir = v; });
  cli.option("-o,--output", "OUT", "OUT.pmtiles, OUT.mbtiles or a folder",
             [&](const std::string& v) { o.output = CliArgs::to_output_path(v); });
  declare_run_options(cli, o, ResumeOption::kNotOffered);
  if (!parse_build_command(cli, o, args, "globe-vectorize export", "PACKAGE")) return kExitOk;
  if (o.inputs.size() != 1)
    throw UsageError("give exactly one line, bundle, point or area package to export");
  s.input = o.inputs[0], s.output = o.output, s.force = o.force;
  const auto kind = package_kind(s.input);
  if (kind != tileformat::PackageKind::kLines && kind != tileformat::PackageKind::kPoints &&
      kind != tileformat::PackageKind::kAreas)
    throw UsageError(s.input +
                     ": globe-vectorize export takes line, bundle, point and area packages; "
                     "terrain and image packages are exported by globe-tiler export");
  Progress progress(o.progress);
  const MvtExportSummary sum =
      kind == tileformat::PackageKind::kPoints  ? export_point_mvt(s, progress)
      : kind == tileformat::PackageKind::kAreas ? export_area_mvt(s, progress)
                                                : export_mvt(s, progress);
  std::ostringstream msg;
  msg.precision(3);
  msg << std::fixed << "globe-vectorize: wrote " << s.output << ": " << sum.tiles << " tiles, zoom "
      << sum.min_zoom << ".." << sum.max_zoom << ", " << sum.features
      << (kind == tileformat::PackageKind::kAreas ? " areas" : " lines and points");
  if (sum.zero_length) msg << " (" << sum.zero_length << " zero-length lines as points)";
  msg << ", " << sum.bytes << " bytes, " << sum.seconds << " s";
  if (sum.labels) msg << ", " << sum.labels << " labels";
  if (!s.style_json.empty()) msg << "; style " << s.style_json;
  if (sum.glyph_files) msg << "; " << sum.glyph_files << " glyph PBFs in " << sum.glyphs_dir;
  progress.note(msg.str());
  return kExitOk;
}

}  // namespace globe
