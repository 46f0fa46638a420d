// `globe-tiler analyze TERRAIN.mbtiles -o ANALYSIS.mbtiles --layers ...`:
// parses options and runs the analysis builder.
#include <algorithm>
#include <bit>
#include <cstdio>
#include <sstream>

#include "analysis/analysis_builder.hpp"
#include "kit/heap_tuning.hpp"
#include "runtime/cli_args.hpp"
#include "runtime/errors.hpp"
#include "tiler_commands.hpp"

namespace globe {
namespace {

std::string layer_names() {
  std::string names;
  for (const auto& l : tileformat::analysis_layers())
    names += (names.empty() ? "" : ", ") + std::string(l.name);
  return names;
}

std::vector<tileformat::AnalysisLayer> parse_layers(const std::string& v) {
  std::vector<tileformat::AnalysisLayer> layers;
  std::stringstream in(v);
  for (std::string name; std::getline(in, name, ',');) {
    if (name == "curvature") {  // both kinds
      layers.push_back(tileformat::AnalysisLayer::kProfileCurvature);
      layers.push_back(tileformat::AnalysisLayer::kPlanCurvature);
      continue;
    }
    if (name == "flow") {  // direction and accumulation
      layers.push_back(tileformat::AnalysisLayer::kFlowDirection);
      layers.push_back(tileformat::AnalysisLayer::kFlowAccumulation);
      continue;
    }
    const auto l = tileformat::analysis_layer_by_name(name);
    if (!l)
      throw UsageError("--layers: unknown layer '" + name + "'; known: " + layer_names() +
                       ", curvature (both curvatures), flow (both flow layers)");
    layers.push_back(*l);
  }
  if (layers.empty()) throw UsageError("--layers: give at least one layer");
  std::sort(layers.begin(), layers.end());
  layers.erase(std::unique(layers.begin(), layers.end()), layers.end());
  return layers;
}

}  // namespace

int run_analyze(const std::vector<std::string>& args) {
  AnalysisSettings s;
  s.layers = parse_layers("slope,aspect");
  CliArgs cli("globe-tiler analyze",
              "globe-tiler analyze TERRAIN.mbtiles -o ANALYSIS.mbtiles [--layers LIST]\n\n"
              "Computes terrain analytics for every sample of every block of a terrain package,\n"
              "from the heights of that zoom, into an analysis package with the same tiles:\n"
              "slope and aspect in degrees (Horn's method, as gdaldem), profile and plan\n"
              "curvature in 1/m (positive where convex), and the sky-view factor (the share of\n"
              "the sky seen within a radius: ambient occlusion), with true ground distances in\n"
              "the geodetic and webmercator tilings. Blocks read their neighbours' samples, so\n"
              "values at block edges are seamless. Flow: D8 direction and accumulation (upstream\n"
              "area in m^2) over the whole finest zoom, depressions filled by priority-flood and\n"
              "flats crossed by the shortest way, out of core within --memory-mb (or, with\n"
              "--flow-method carve, routed by least cost in memory); coarser zooms follow the\n"
              "rivers. 'globe-tiler extract ANALYSIS --layer NAME' writes one layer\n"
              "as a GeoTIFF.");
  cli.option("--layers", "LIST",
             "comma-separated: " + layer_names() +
                 ", curvature (both curvatures), flow (direction and accumulation); default "
                 "slope,aspect",
             [&](const std::string& v) { s.layers = parse_layers(v); });
  cli.option("--skyview-directions", "N", "azimuths of the sky-view horizon scan (default 16)",
             [&](const std::string& v) {
               s.skyview.directions = CliArgs::to_int("--skyview-directions", v, 4, 360);
             });
  cli.option("--skyview-radius", "METRES",
             "how far the sky-view scan looks for the horizon (default 10000); past two blocks "
             "around a block the rays go on in the coarser zooms, so only a terrain without "
             "its top zooms (--min-zoom) cuts it: info says what radius each zoom reaches",
             [&](const std::string& v) {
               s.skyview.radius_m = CliArgs::to_double("--skyview-radius", v);
               if (!(s.skyview.radius_m > 0 && s.skyview.radius_m <= 1e6))
                 throw UsageError("--skyview-radius: give metres, more than 0 and at most 1000000");
             });
  cli.option("--memory-mb", "MB",
             "memory for the flow solver's working set (default 1024); a larger DEM is solved "
             "out of core in chunks, with scratch files next to the output",
             [&](const std::string& v) {
               s.memory_mb = uint64_t(CliArgs::to_int("--memory-mb", v, 1, 1 << 22));
             });
  cli.option("--flow-chunk", "N",
             "cells a side of the flow solver's chunks, a power of two from 64 (default: the "
             "whole grid as one chunk where it fits --memory-mb, the least work but solved on "
             "one thread; else the largest that fits). Smaller chunks are solved in parallel: "
             "less wall time on many cores, more CPU time; the result is the same",
             [&](const std::string& v) {
               const int n = CliArgs::to_int("--flow-chunk", v, 64, 1 << 24);
               if (!std::has_single_bit(unsigned(n)))
                 throw UsageError("--flow-chunk: give a power of two (64, 128, ... 16777216)");
               s.flow_chunk = n;
             });
  cli.option("--flow-method", "fill|carve",
             "how water crosses depressions and flats. fill (default): depressions filled by "
             "priority-flood, flats and filled depressions routed; solved out of core and in "
             "parallel for any size, the same bytes for any --memory-mb. carve: least-cost "
             "routing (GRASS r.watershed's search): water runs through a depression's rim along "
             "the lowest way, no filling; closest to r.watershed on large flat lowlands (coarse "
             "continental DEMs); holds the whole finest zoom in memory (26 bytes a cell within "
             "--memory-mb), on one thread",
             [&](const std::string& v) {
               if (v == "fill")
                 s.flow_method = flow::FlowMethod::kFill;
               else if (v == "carve")
                 s.flow_method = flow::FlowMethod::kCarve;
               else
                 throw UsageError("--flow-method: give fill or carve, not '" + v + "'");
             });
  cli.option("-o,--output", "OUT.mbtiles", "output analysis package",
             [&](const std::string& v) { s.output = CliArgs::to_output_path(v); });
  declare_run_options(cli, s);
  declare_shard_options(cli, s);
  if (!parse_build_command(cli, s, args, "globe-tiler analyze", "TERRAIN.mbtiles")) return kExitOk;
  if (s.inputs.size() != 1) throw UsageError("give exactly one terrain package");
  const auto flow = [&](tileformat::AnalysisLayer l) {
    return std::find(s.layers.begin(), s.layers.end(), l) != s.layers.end();
  };
  if (s.shard && (flow(tileformat::AnalysisLayer::kFlowDirection) ||
                  flow(tileformat::AnalysisLayer::kFlowAccumulation)))
    throw UsageError(
        "--shard: the flow layers cannot be sharded (water crosses every shard border: flow "
        "needs the whole DEM at once); shard the other layers and build flow on one machine");
  // The flow solver's arrays are chunk-sized, allocated and freed per chunk
  // and per pass: without this, page faults took a third of its CPU.
  if (flow(tileformat::AnalysisLayer::kFlowDirection) ||
      flow(tileformat::AnalysisLayer::kFlowAccumulation))
    reuse_large_arrays();
  Progress progress(s.progress);
  const AnalysisSummary sum = build_analysis(s, progress);
  std::ostringstream o;
  o.precision(3);
  o << std::fixed << "globe-tiler: wrote " << s.output << ": " << sum.tiles << " tiles ("
    << sum.unique_blobs << " unique), " << sum.file_bytes << " bytes, " << sum.seconds << " s";
  progress.note(o.str());
  if (!sum.flow_note.empty()) progress.note("globe-tiler: " + sum.flow_note);
  return kExitOk;
}

}  // namespace globe
