// `globe-tiler info`, `validate` and `extract`: the kinds of package the
// tiler reads, one row each (adding a kind adds a row), and the commands
// that parse their arguments and call the package's row.
#include <filesystem>

#include "geo/gdal_dataset.hpp"
#include "inspect/inspect_commands.hpp"
#include "kit/kind_inspection.hpp"
#include "runtime/cli_args.hpp"
#include "runtime/errors.hpp"
#include "tiler_commands.hpp"

namespace globe {

// Each in its kind's file: terrain_inspect.cpp, image_inspect.cpp, analysis_inspect.cpp.
extern const KindInspection kTerrainInspection, kImageInspection, kAnalysisInspection;

namespace {

constexpr const KindInspection* kTilerKinds[] = {&kTerrainInspection, &kImageInspection,
                                                 &kAnalysisInspection};
constexpr const char* kKindList = "terrain, image or analysis";

}  // namespace

int run_info(const std::vector<std::string>& args) {
  return run_info_command("globe-tiler", kKindList, kTilerKinds, args);
}

int run_validate(const std::vector<std::string>& args) {
  return run_validate_command("globe-tiler", kKindList, kTilerKinds, args);
}

int run_extract(const std::vector<std::string>& args) {
  ExtractRequest rq;
  std::optional<int> zoom;
  CliArgs cli("globe-tiler extract",
              "globe-tiler extract PACKAGE --zoom Z [--bbox W,S,E,N] -o OUT.tif\n\n"
              "Writes one zoom of a package as a GeoTIFF in the tiling CRS. Terrain: the decoded\n"
              "heights as Float64, NaN (nodata) where there is no data. Imagery: the tile pixels,\n"
              "gray or RGB plus an alpha band. Analysis: one layer (--layer) as Float32.");
  cli.option("--zoom", "Z", "zoom level to extract",
             [&](const std::string& v) { zoom = CliArgs::to_int("--zoom", v, 0, 30); });
  cli.option("--bbox", "W,S,E,N", "only tiles intersecting this lon/lat box",
             [&](const std::string& v) { rq.bbox = CliArgs::to_doubles("--bbox", v, 4); });
  cli.option("--layer", "NAME",
             "analysis packages: the layer to write, any the package holds (slope, aspect, "
             "profile_curvature, plan_curvature, skyview, flow_direction, flow_accumulation), "
             "Float32 in its unit, NaN where it has no value",
             [&](const std::string& v) { rq.layer = v; });
  cli.option("-o,--output", "OUT.tif", "output GeoTIFF",
             [&](const std::string& v) { rq.output = CliArgs::to_output_path(v); });
  cli.flag("--force", "replace an existing output", [&] { rq.force = true; });
  auto positional = cli.parse_command(args, 1, 1, "PACKAGE");
  if (!positional) return kExitOk;
  if (!zoom) throw UsageError("--zoom is required");
  if (rq.output.empty()) throw UsageError("no output given; add -o OUT.tif");
  rq.package = (*positional)[0];
  rq.zoom = *zoom;
  std::error_code ec;
  if (std::filesystem::exists(rq.output, ec) && !rq.force)
    throw OutputError(rq.output + ": output exists; pass --force to replace it");
  gdal_init();
  return inspection_for(rq.package, kTilerKinds, "globe-tiler extract").extract(rq);
}

}  // namespace globe
