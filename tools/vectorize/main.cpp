// globe-vectorize: vector data (any OGR source) -> line-cluster packages, and
// tools to inspect them. Dispatch and error reporting: tools/common/kit/command_tool.
#include "kit/command_tool.hpp"
#include "vectorize_commands.hpp"

namespace {

const char* kUsage =
    "usage: globe-vectorize COMMAND [options]\n"
    "\n"
    "commands:\n"
    "  lines INPUT... -o OUT.mbtiles      lines, polygon outlines and points (Shapefile,\n"
    "                                     GeoPackage, GeoJSON, OSM, ...) -> line-cluster package\n"
    "  points INPUT... -o OUT.mbtiles --fields A,B,...   places with values (OGR points,\n"
    "                                     CSV with --xy) -> point package for charts\n"
    "  areas INPUT... -o OUT.mbtiles      polygons (countries, land use, tracts; any OGR\n"
    "                                     source) -> area package, with --choropleth classes\n"
    "  bundle FLOWS --network NET... -o OUT.mbtiles   origin-destination flows routed\n"
    "                                     along a network, bundled and smoothed -> line package\n"
    "  info PACKAGE                       metadata, classes or fields, zooms, tiles, contents\n"
    "  validate PACKAGE                   decode every tile, recheck every cluster grid\n"
    "  extract PACKAGE --zoom Z -o OUT.gpkg   decoded lines or places of one zoom as vector data\n"
    "  merge SHARD... -o OUT.mbtiles      join the shards of a `lines` or `areas --shard I/N`\n"
    "                                     build\n"
    "  export PACKAGE -o OUT.pmtiles      lines, points or areas as vector tiles (MVT) for web\n"
    "                                     maps, a MapLibre style\n"
    "\n"
    "Run 'globe-vectorize COMMAND --help' for the options of a command.\n"
    "Exit codes: 0 ok, 1 bad input data, 2 bad usage, 3 output cannot be written,\n"
    "            4 internal error, 5 validate found warnings only.\n";

}  // namespace

int main(int argc, char** argv) {
  return globe::run_command_tool("globe-vectorize", GLOBE_VERSION, kUsage,
                                 {{"lines", globe::run_lines},
                                  {"info", globe::run_lines_info},
                                  {"validate", globe::run_lines_validate},
                                  {"extract", globe::run_lines_extract},
                                  {"merge", globe::run_lines_merge},
                                  {"points", globe::run_points},
                                  {"areas", globe::run_areas},
                                  {"bundle", globe::run_bundle},
                                  {"export", globe::run_export}},
                                 argc, argv);
}
