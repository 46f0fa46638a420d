// `globe-vectorize bundle`: parses options into BundleSettings, builds, and
// prints the summary.
#include <sstream>

#include "bundle/bundle_builder.hpp"
#include "lines/lines_options.hpp"
#include "runtime/cli_args.hpp"
#include "runtime/errors.hpp"
#include "vectorize_commands.hpp"

namespace globe {

namespace {

ColumnPair column_pair(const std::string& option, const std::string& v) {
  const std::vector<std::string> names = CliArgs::to_names(option, v, 2);
  return {names[0], names[1]};
}

// The reference network and the flows: --network … --weight.
void declare_network_and_flow_options(CliArgs& cli, BundleSettings& s) {
  cli.option("--network", "FILE", "reference network: any OGR lines (repeatable; required)",
             [&](const std::string& v) { s.network.push_back(v); });
  cli.option("--network-layer", "NAME", "only this layer of the network (repeatable)",
             [&](const std::string& v) { s.net.layers.push_back(v); });
  cli.option("--cost-field", "FIELD",
             "network field holding each line's cost (default: its geodesic length)",
             [&](const std::string& v) { s.net.cost_field = v; });
  cli.option("--snap-m", "M", "network vertices closer than this are one node (default 1 m)",
             [&](const std::string& v) {
               s.net.snap_m = CliArgs::to_double("--snap-m", v);
               if (!(s.net.snap_m > 0) || s.net.snap_m > 100000)
                 throw UsageError("--snap-m must be within 0..100000 m (above 0)");
             });
  cli.option("--max-snap", "M",
             "a place farther than this from every network node is unrouted (default 25000 m)",
             [&](const std::string& v) {
               s.max_snap_m = CliArgs::to_double("--max-snap", v);
               if (!(s.max_snap_m >= 0)) throw UsageError("--max-snap must be 0 or more metres");
             });
  cli.option("--from", "LONCOL,LATCOL", "columns of each connection's origin (longitude, latitude)",
             [&](const std::string& v) { s.flow.from_xy = column_pair("--from", v); });
  cli.option("--to", "LONCOL,LATCOL", "columns of each connection's destination",
             [&](const std::string& v) { s.flow.to_xy = column_pair("--to", v); });
  cli.option("--from-id", "COL", "column of each origin's id in --locations",
             [&](const std::string& v) { s.flow.from_id = v; });
  cli.option("--to-id", "COL", "column of each destination's id in --locations",
             [&](const std::string& v) { s.flow.to_id = v; });
  cli.option("--locations", "FILE",
             "places of the ids: OGR points, or CSV with longitude/latitude columns",
             [&](const std::string& v) { s.flow.locations = v; });
  cli.option("--id-field", "COL", "the id column of --locations",
             [&](const std::string& v) { s.flow.id_field = v; });
  cli.option("--label-field", "COL",
             "label the connections' ends (docs/labels.md): a column of --locations naming\n"
             "                              them (e.g. city; the id where empty), or the id\n"
             "                              column itself; ranked by the weight through them",
             [&](const std::string& v) { s.flow.label_field = v; });
  cli.option("--locations-xy", "LONCOL,LATCOL",
             "coordinate columns of a CSV --locations (default: longitude/lon/lng/x, "
             "latitude/lat/y)",
             [&](const std::string& v) { s.flow.locations_xy = column_pair("--locations-xy", v); });
  cli.option("--weight", "COL", "numeric column of each connection's weight (default: 1 each)",
             [&](const std::string& v) { s.flow.weight = v; });
}

// How bundles are smoothed, classed and drawn: --corridor-px …
// --no-junction-tangents.
void declare_bundle_drawing_options(CliArgs& cli, BundleSettings& s) {
  cli.option("--corridor-px", "PX",
             "how far (pixels of each zoom) a smoothed bundle may stray from the network "
             "(default 4; 0 = follow it exactly)",
             [&](const std::string& v) {
               s.corridor_px = CliArgs::to_double("--corridor-px", v);
               if (!(s.corridor_px >= 0) || s.corridor_px > 256)
                 throw UsageError("--corridor-px must be within 0..256 pixels");
             });
  cli.option("--unrouted", "straight|drop",
             "connections that cannot be routed: drawn as straight (geodesic) lines in class "
             "unrouted (default), or left out",
             [&](const std::string& v) {
               if (v != "straight" && v != "drop")
                 throw UsageError("--unrouted: '" + v + "' is not straight or drop");
               s.unrouted = v == "straight" ? Unrouted::kStraight : Unrouted::kDrop;
             });
  cli.option("--weight-classes", "N",
             "classes weight-1..weight-N by the square root of a bundle's share of the\n"
             "                              heaviest bundle's weight (default 6)",
             [&](const std::string& v) {
               s.weight_classes = CliArgs::to_int("--weight-classes", v, 1, 64);
             });
  cli.option("--widths", "MIN,MAX", "line widths of weight-1 and weight-N in px (default 1,9)",
             [&](const std::string& v) {
               const std::vector<double> w = CliArgs::to_doubles("--widths", v, 2);
               if (!(w[0] > 0) || !(w[1] >= w[0]) || w[1] > 64)
                 throw UsageError("--widths: expected 0 < MIN <= MAX <= 64 pixels");
               s.min_width = w[0];
               s.max_width = w[1];
             });
  cli.option("--opacities", "MIN,MAX", "opacities of weight-1 and weight-N (default 0.45,1)",
             [&](const std::string& v) {
               const std::vector<double> o = CliArgs::to_doubles("--opacities", v, 2);
               if (!(o[0] > 0) || !(o[1] >= o[0]) || o[1] > 1)
                 throw UsageError("--opacities: expected 0 < MIN <= MAX <= 1");
               s.min_opacity = o[0];
               s.max_opacity = o[1];
             });
  cli.option("--significance", "SHARE",
             "at each zoom, draw a flow only where it carries at least this share of the\n"
             "                              heaviest flow in a view (5x3 tiles) around it; zooming "
             "in\n"
             "                              shows the lighter ones (default 0.02; 0 = all at every "
             "zoom)",
             [&](const std::string& v) {
               s.significance = CliArgs::to_double("--significance", v);
               if (!(s.significance >= 0 && s.significance <= 1))
                 throw UsageError("--significance: expected a share from 0 to 1");
             });
  cli.option("--min-weight", "W",
             "never draw bundles or unrouted lines lighter than W (they stay in the features\n"
             "                              table; default 0)",
             [&](const std::string& v) {
               s.min_weight = CliArgs::to_double("--min-weight", v);
               if (!(s.min_weight >= 0)) throw UsageError("--min-weight must be 0 or more");
             });
  cli.flag("--no-junction-tangents",
           "let curves turn where one bundle hands over to the next (default: they share a\n"
           "                              tangent there, no kink)",
           [&] { s.smooth_junctions = false; });
}

// The one-paragraph summary of a finished build.
std::string summary_text(const BundleSummary& sum, const std::string& output) {
  std::ostringstream o;
  o.precision(3);
  o << std::fixed << "globe-vectorize: wrote " << output << ": " << sum.connections
    << " connections from " << sum.rows << " rows (" << sum.bad_rows << " bad rows, "
    << sum.zero_weights << " of weight 0): " << sum.routed << " routed, " << sum.unrouted
    << " unrouted (" << sum.unsnapped << " beyond --max-snap, " << sum.same_node << " on one node, "
    << sum.disconnected << " across components); " << sum.bundles << " bundles ("
    << sum.hidden_at_min_zoom << " flows too light to draw at zoom " << sum.min_zoom << ", "
    << sum.never_drawn << " under --min-weight), mean detour " << sum.mean_detour << ", ink ratio "
    << sum.ink_ratio << "; network " << sum.network_nodes << " nodes, " << sum.network_edges
    << " edges, " << sum.components << " components, reduced to " << sum.reduced_nodes
    << " nodes and " << sum.reduced_edges << " edges; zoom " << sum.min_zoom << ".." << sum.max_zoom
    << ", " << sum.curve_levels << " curves (" << sum.curve_points << " points), " << sum.tiles
    << " tiles (" << sum.unique_blobs << " unique), " << sum.file_bytes << " bytes, " << sum.seconds
    << " s (";
  for (size_t i = 0; i < sum.stage_seconds.size(); ++i)
    o << (i ? ", " : "") << sum.stage_seconds[i].first << " " << sum.stage_seconds[i].second;
  o << ")";
  for (const std::string& e : sum.bad_row_examples)
    o << "\n  bad row: " << e;
  return o.str();
}

}  // namespace

int run_bundle(const std::vector<std::string>& args) {
  BundleSettings s;
  CliArgs cli("globe-vectorize bundle",
              "globe-vectorize bundle FLOWS --network NETWORK... -o OUT.mbtiles [options]\n\n"
              "Routes origin-destination flows (a CSV file or any OGR source, one connection\n"
              "per row) along a reference network (roads, rails, airways: any OGR lines), so\n"
              "flows sharing a corridor merge into bundles, smooths each bundle into a curve\n"
              "that stays within --corridor-px of the network at every zoom, and writes a\n"
              "line-cluster package: bundles in classes weight-1.. by their total weight\n"
              "(wider and darker with weight), unrouted connections straight (class\n"
              "unrouted), and a features row per connection naming its bundles\n"
              "(docs/bundles.md).\n\n"
              "examples:\n"
              "  globe-vectorize bundle flights.csv --from-id origin --to-id destination\n"
              "      --weight count --locations airports.csv --id-field iata\n"
              "      --network airways.geojson -o flights.mbtiles\n"
              "  globe-vectorize bundle commutes.csv --from hlon,hlat --to wlon,wlat\n"
              "      --network roads.gpkg --network-layer roads -o commutes.mbtiles");
  declare_area_options(cli, s,
                       "CRS of the network and locations files without one (default: theirs)",
                       "finest zoom (default: where the network's median segment spans 4 px, "
                       "at least 6 and at most 18)");
  declare_network_and_flow_options(cli, s);
  declare_bundle_drawing_options(cli, s);
  cli.option("--like", "PACKAGE",
             "use the tiling of this package (e.g. a local terrain), so tile ids match",
             [&](const std::string& v) { s.like = v; });
  declare_line_tile_options(cli, s);
  declare_run_options(cli, s);
  if (!parse_build_command(cli, s, args, "globe-vectorize bundle", "flows file (see --help)"))
    return kExitOk;
  if (s.inputs.size() != 1)
    throw UsageError("give one flows file (got " + std::to_string(s.inputs.size()) +
                     "); the network goes in --network");
  if (s.network.empty())
    throw UsageError(
        "--network is required: the lines connections are routed along (e.g. "
        "--network roads.gpkg)");
  if (!s.like.empty() && (s.tiling != tileformat::Scheme::kWebMercator || !s.t_srs.empty()))
    throw UsageError("--like takes the tiling from the package; drop --tiling/--t_srs");
  s.flows = s.inputs[0];
  s.net.s_srs = s.flow.s_srs = s.s_srs;
  // The network and the locations identify the build too (--resume, metadata).
  s.inputs.insert(s.inputs.end(), s.network.begin(), s.network.end());
  if (!s.flow.locations.empty()) s.inputs.push_back(s.flow.locations);

  Progress progress(s.progress);
  const BundleSummary sum = build_bundles(s, progress);
  progress.note(summary_text(sum, s.output));
  return kExitOk;
}

}  // namespace globe
