// `globe-tiler terrain`: parses options into TerrainSettings, plans, builds,
// and prints the summary.
#include <cstdio>
#include <sstream>
#include <thread>

#include "runtime/cli_args.hpp"
#include "runtime/errors.hpp"
#include "terrain/dem_plan.hpp"
#include "terrain/terrain_builder.hpp"
#include "tiler_commands.hpp"

namespace globe {

int run_terrain(const std::vector<std::string>& args) {
  TerrainSettings s;
  CliArgs cli(
      "globe-tiler terrain",
      "globe-tiler terrain INPUT... -o OUT.mbtiles [options]\n\n"
      "Turns DEMs that GDAL reads (any CRS; several inputs form one mosaic, later inputs\n"
      "on top) into a terrain package: MBlocks with KPatch error trees in one SQLite file.");
  declare_area_options(
      cli, s, "CRS of the inputs, for files without one or with a wrong one",
      "finest zoom (default: where the sample spacing reaches the source resolution)");
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
  declare_run_options(cli, s);
  declare_shard_options(cli, s);
  if (!parse_build_command(cli, s, args, "globe-tiler terrain", "input DEM (see --help)"))
    return kExitOk;

  Progress progress(s.progress);
  DemPlan plan = plan_terrain(s);
  {
    std::ostringstream o;
    o << "globe-tiler: " << plan.sources.size() << " input(s), tiling "
      << tileformat::scheme_name(plan.tiling.scheme) << ", zoom " << plan.min_zoom << ".."
      << plan.max_zoom << ", block " << s.block_size << ", height step " << plan.step_m
      << " m, source pixel " << plan.source_resolution << " (tiling units)";
    if (!plan.left_out.empty()) o << "\nglobe-tiler: left out: " << plan.left_out;
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
