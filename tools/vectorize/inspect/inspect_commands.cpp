// `globe-vectorize info`, `validate` and `extract`: the kinds of package
// globe-vectorize reads, one row each (adding a kind adds a row), and the
// commands that parse their arguments and call the package's row.
#include "kit/kind_inspection.hpp"
#include "runtime/cli_args.hpp"
#include "runtime/errors.hpp"
#include "vectorize_commands.hpp"

namespace globe {

// Each in its kind's file: lines_inspect.cpp, points_inspect.cpp, areas_inspect.cpp.
extern const KindInspection kLinesInspection, kPointsInspection, kAreasInspection;

namespace {

constexpr const KindInspection* kVectorizeKinds[] = {&kLinesInspection, &kPointsInspection,
                                                     &kAreasInspection};
constexpr const char* kKindList = "line-cluster, point or area";

}  // namespace

int run_lines_info(const std::vector<std::string>& args) {
  return run_info_command("globe-vectorize", kKindList, kVectorizeKinds, args);
}

int run_lines_validate(const std::vector<std::string>& args) {
  return run_validate_command("globe-vectorize", kKindList, kVectorizeKinds, args);
}

int run_lines_extract(const std::vector<std::string>& args) {
  ExtractRequest rq;
  std::optional<int> zoom;
  CliArgs cli("globe-vectorize extract",
              "globe-vectorize extract PACKAGE --zoom Z -o OUT.gpkg\n\n"
              "Writes the lines (and points) of zoom Z, clipped to their tiles, as vector data\n"
              "(GeoPackage; .geojson, .shp, .fgb by extension) in the tiling CRS. Of a point\n"
              "package: its places with their values (layer places); of an area package: its\n"
              "polygons, each clipped to its own tile (layer polygons).");
  cli.option("--zoom", "Z", "zoom level to extract",
             [&](const std::string& v) { zoom = CliArgs::to_int("--zoom", v, 0, 30); });
  cli.option("-o,--output", "OUT.gpkg", "output file",
             [&](const std::string& v) { rq.output = CliArgs::to_output_path(v); });
  cli.flag("--force", "replace an existing output", [&] { rq.force = true; });
  cli.flag("-q,--quiet", "no summary on stderr", [&] { rq.quiet = true; });
  auto positional = cli.parse_command(args, 1, 1, "PACKAGE");
  if (!positional) return kExitOk;
  if (!zoom) throw UsageError("--zoom is required");
  if (rq.output.empty()) throw UsageError("no output given; add -o OUT.gpkg");
  rq.package = (*positional)[0];
  rq.zoom = *zoom;
  return inspection_for(rq.package, kVectorizeKinds, "globe-vectorize extract").extract(rq);
}

}  // namespace globe
