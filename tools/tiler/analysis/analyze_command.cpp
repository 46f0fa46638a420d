// `globe-tiler analyze TERRAIN.mbtiles -o ANALYSIS.mbtiles --layers ...`:
// parses options and runs the analysis builder.
#include <cstdio>
#include <sstream>

#include "analysis_builder.hpp"
#include "cli_args.hpp"
#include "commands.hpp"
#include "errors.hpp"

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
    const auto l = tileformat::analysis_layer_by_name(name);
    if (!l)
      throw UsageError("--layers: unknown layer '" + name + "'; known: " + layer_names() +
                       ", curvature (both curvatures)");
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
              "curvature in 1/m (positive where convex), with true ground distances in the\n"
              "geodetic and webmercator tilings. Blocks read their neighbours' samples, so\n"
              "values at block edges are seamless. 'globe-tiler extract ANALYSIS --layer NAME'\n"
              "writes one layer as a GeoTIFF.");
  cli.option("--layers", "LIST",
             "comma-separated: " + layer_names() + ", or curvature (both); default slope,aspect",
             [&](const std::string& v) { s.layers = parse_layers(v); });
  cli.option("-o,--output", "OUT.mbtiles", "output analysis package",
             [&](const std::string& v) { s.output = v; });
  declare_run_options(cli, s);
  if (!parse_build_command(cli, s, args, "globe-tiler analyze", "TERRAIN.mbtiles")) return kExitOk;
  if (s.inputs.size() != 1) throw UsageError("give exactly one terrain package");
  Progress progress(s.progress);
  const AnalysisSummary sum = build_analysis(s, progress);
  std::ostringstream o;
  o.precision(3);
  o << std::fixed << "globe-tiler: wrote " << s.output << ": " << sum.tiles << " tiles ("
    << sum.unique_blobs << " unique), " << sum.file_bytes << " bytes, " << sum.seconds << " s";
  progress.note(o.str());
  return kExitOk;
}

}  // namespace globe
