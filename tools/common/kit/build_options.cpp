// Shared build options (see build_options.hpp).
#include "kit/build_options.hpp"

#include <filesystem>

#include "runtime/errors.hpp"

namespace globe {

void declare_area_options(CliArgs& cli, BuildOptions& o, const std::string& s_srs_help,
                          const std::string& max_zoom_help) {
  cli.option("-o,--output", "OUT.mbtiles",
             "output package (written as OUT.mbtiles.tmp, renamed when complete)",
             [&o](const std::string& v) { o.output = CliArgs::to_output_path(v); });
  cli.option(
      "--tiling", "SCHEME",
      "webmercator (default, EPSG:3857), geodetic (EPSG:4326, 2x1 roots) or local",
      [&o](const std::string& v) {
        const auto scheme = tileformat::parse_scheme(v);
        if (!scheme)
          throw UsageError("--tiling: '" + v + "' is not one of webmercator, geodetic, local");
        o.tiling = *scheme;
      });
  cli.option("--t_srs", "CRS", "CRS of the local tiling (default: the first input's CRS)",
             [&o](const std::string& v) { o.t_srs = v; });
  cli.option("--s_srs", "CRS", s_srs_help, [&o](const std::string& v) { o.s_srs = v; });
  cli.option("--min-zoom", "Z", "coarsest zoom written (default 0)",
             [&o](const std::string& v) { o.min_zoom = CliArgs::to_int("--min-zoom", v, 0, 24); });
  cli.option("--max-zoom", "Z", max_zoom_help,
             [&o](const std::string& v) { o.max_zoom = CliArgs::to_int("--max-zoom", v, 0, 24); });
  cli.option("--bbox", "W,S,E,N", "only this area, in degrees of longitude/latitude",
             [&o](const std::string& v) { o.bbox = CliArgs::to_doubles("--bbox", v, 4); });
}

void declare_run_options(CliArgs& cli, BuildOptions& o, ResumeOption resume) {
  cli.option("-j,--threads", "N",
             "worker threads (default: all cores); output is identical for any N",
             [&o](const std::string& v) { o.threads = CliArgs::to_int("--threads", v, 1, 1024); });
  cli.option("--progress", "MODE", "'json': one JSON object per line on stderr, for scripts",
             [&o](const std::string& v) {
               if (v != "json") throw UsageError("--progress: only 'json' is supported");
               o.progress = ProgressMode::kJson;
             });
  cli.flag("--force", "replace an existing output", [&o] { o.force = true; });
  if (resume == ResumeOption::kOffered)
    cli.flag("--resume",
             "continue the build a kill or crash interrupted (OUT.mbtiles.tmp) instead of "
             "starting over; same inputs and options required; the result is identical to an "
             "uninterrupted run",
             [&o] { o.resume = true; });
  cli.flag("-q,--quiet", "no progress or summary on stderr", [&o] { o.quiet = true; });
}

std::string build_key(const BuildOptions& o) {
  std::string key = o.command_line;
  for (const std::string& in : o.inputs) {
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(in, ec);
    const auto time = std::filesystem::last_write_time(in, ec);
    key += "\n" + in + " " + std::to_string(ec ? 0 : bytes) + " " +
           std::to_string(ec ? 0 : time.time_since_epoch().count());
  }
  return key;
}

bool parse_build_command(CliArgs& cli, BuildOptions& o, const std::vector<std::string>& args,
                         const std::string& program, const std::string& input_what) {
  auto positional = cli.parse_command(args, 1, SIZE_MAX, input_what);
  if (!positional) return false;
  o.inputs = *positional;
  if (o.output.empty()) throw UsageError("no output given; add -o OUT.mbtiles");
  // Before any plan or work: an existing output is refused at once.
  std::error_code ec;
  if (!o.force && std::filesystem::exists(o.output, ec))
    throw OutputError(o.output + ": output exists; pass --force to replace it");
  if (o.bbox) {
    const auto& b = *o.bbox;
    if (!(b[0] < b[2] && b[1] < b[3]) || b[0] < -540 || b[2] > 540 || b[1] < -90 || b[3] > 90)
      throw UsageError(
          "--bbox: expected west,south,east,north in degrees with west < east, south < north");
  }
  if (o.min_zoom && o.max_zoom && *o.min_zoom > *o.max_zoom)
    throw UsageError("--min-zoom " + std::to_string(*o.min_zoom) + " is larger than --max-zoom " +
                     std::to_string(*o.max_zoom));
  if (o.split_zoom && !o.shard) throw UsageError("--split-zoom needs --shard I/N");
  if (o.quiet) o.progress = ProgressMode::kQuiet;
  o.command_line = CliArgs::reproducible_command_line(program, args);
  return true;
}

}  // namespace globe
