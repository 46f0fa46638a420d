// `globe-tiler terrain`: parses options into TerrainSettings, plans, builds,
// and prints the summary.
#include <cstdio>
#include <sstream>
#include <thread>

#include "cli_args.hpp"
#include "commands.hpp"
#include "dem_plan.hpp"
#include "errors.hpp"
#include "terrain_builder.hpp"

namespace globe {

int run_terrain(const std::vector<std::string>& args, const std::string&) {
  TerrainSettings s;
  bool quiet = false;
  CliArgs cli(
      "globe-tiler terrain",
      "globe-tiler terrain INPUT... -o OUT.mbtiles [options]\n\n"
      "Turns DEMs that GDAL reads (any CRS; several inputs form one mosaic, later inputs\n"
      "on top) into a terrain package: MBlocks with KPatch error trees in one SQLite file.");
  cli.option("-o,--output", "OUT.mbtiles",
             "output package (written as OUT.mbtiles.tmp, renamed when complete)",
             [&](const std::string& v) { s.output = v; });
  cli.option("--tiling", "SCHEME",
             "webmercator (default, EPSG:3857), geodetic (EPSG:4326, 2x1 roots) or local",
             [&](const std::string& v) { s.tiling = v; });
  cli.option("--t_srs", "CRS", "CRS of the local tiling (default: the first input's CRS)",
             [&](const std::string& v) { s.t_srs = v; });
  cli.option("--s_srs", "CRS", "CRS of the inputs, for files without one or with a wrong one",
             [&](const std::string& v) { s.s_srs = v; });
  cli.option("--min-zoom", "Z", "coarsest zoom written (default 0)",
             [&](const std::string& v) { s.min_zoom = CliArgs::to_int("--min-zoom", v, 0, 24); });
  cli.option("--max-zoom", "Z",
             "finest zoom (default: where the sample spacing reaches the source resolution)",
             [&](const std::string& v) { s.max_zoom = CliArgs::to_int("--max-zoom", v, 0, 24); });
  cli.option("--bbox", "W,S,E,N", "only this area, in degrees of longitude/latitude",
             [&](const std::string& v) { s.bbox = CliArgs::to_doubles("--bbox", v, 4); });
  cli.option(
      "--block-size", "N", "samples per block side, 2^k+1 (default 257)",
      [&](const std::string& v) { s.block_size = CliArgs::to_int("--block-size", v, 3, 4097); });
  cli.option("--precision", "METRES",
             "height step of the quantization grid (default 1 for integer DEMs, 0.01 otherwise)",
             [&](const std::string& v) { s.precision = CliArgs::to_double("--precision", v); });
  cli.option("--resampling", "METHOD",
             "near, bilinear (default), cubic, cubicspline, lanczos, average, ...",
             [&](const std::string& v) { s.resampling = v; });
  cli.option("--nodata", "VALUE", "input value meaning 'no data' (overrides the files' own)",
             [&](const std::string& v) { s.nodata = CliArgs::to_double("--nodata", v); });
  cli.option("-j,--threads", "N",
             "worker threads (default: all cores); output is identical for any N",
             [&](const std::string& v) { s.threads = CliArgs::to_int("--threads", v, 1, 1024); });
  cli.option("--progress", "MODE", "'json': one JSON object per line on stderr, for scripts",
             [&](const std::string& v) {
               if (v != "json") throw UsageError("--progress: only 'json' is supported");
               s.progress = ProgressMode::kJson;
             });
  cli.flag("--force", "replace an existing output", [&] { s.force = true; });
  cli.flag("-q,--quiet", "no progress or summary on stderr", [&] { quiet = true; });
  auto positional = cli.parse_command(args, 1, SIZE_MAX, "input DEM (see --help)");
  if (!positional) return kExitOk;
  s.inputs = *positional;
  if (s.output.empty()) throw UsageError("no output given; add -o OUT.mbtiles");
  if (quiet) s.progress = ProgressMode::kQuiet;
  s.command_line = CliArgs::reproducible_command_line("globe-tiler terrain", args);

  Progress progress(s.progress);
  DemPlan plan = plan_terrain(s);
  {
    std::ostringstream o;
    o << "globe-tiler: " << plan.sources.size() << " input(s), tiling " << plan.tiling.scheme
      << ", zoom " << plan.min_zoom << ".." << plan.max_zoom << ", block " << s.block_size
      << ", height step " << plan.step_m << " m, source pixel " << plan.source_resolution
      << " (tiling units)";
    progress.note(o.str());
  }
  const BuildSummary sum = build_terrain(plan, s, progress);
  std::ostringstream o;
  o.precision(3);
  o << std::fixed << "globe-tiler: wrote " << s.output << ": " << sum.tiles << " tiles ("
    << sum.unique_blobs << " unique), " << sum.file_bytes << " bytes, "
    << (sum.samples ? 8.0 * sum.blob_bytes / sum.samples : 0.0) << " bits/sample, " << sum.seconds
    << " s";
  progress.note(o.str());
  return kExitOk;
}

}  // namespace globe
