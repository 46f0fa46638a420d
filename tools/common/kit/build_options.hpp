// The options every package-building command shares (inputs, output, tiling,
// zoom range, area, threads, progress), their declaration on the command
// line, and the checks after parsing. Command settings derive from it.
#pragma once

#include <algorithm>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "kit/progress.hpp"
#include "kit/shard_plan.hpp"
#include "runtime/cli_args.hpp"
#include "tileformat/tiling.hpp"

namespace globe {

struct BuildOptions {
  std::vector<std::string> inputs;
  std::string output;
  tileformat::Scheme tiling = tileformat::Scheme::kWebMercator;
  std::string t_srs;  // local tiling only
  std::string s_srs;  // overrides/assigns the inputs' CRS
  std::optional<int> min_zoom, max_zoom;
  std::optional<std::vector<double>> bbox;  // lon/lat: west,south,east,north
  int threads = 0;                          // 0 = all cores
  bool force = false;
  bool resume = false;  // continue an interrupted build's OUT.tmp
  bool quiet = false;
  ProgressMode progress = ProgressMode::kAuto;
  std::string command_line;        // recorded in metadata (see reproducible_command_line)
  std::optional<ShardSpec> shard;  // --shard I/N (builders that support it)
  std::optional<int> split_zoom;   // --split-zoom

  // -j, or all cores when not given.
  int worker_threads() const {
    return threads > 0 ? threads
                       : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  }
};

// -o, --tiling, --t_srs, --s_srs, --min-zoom, --max-zoom, --bbox.
void declare_area_options(CliArgs& cli, BuildOptions& o, const std::string& s_srs_help,
                          const std::string& max_zoom_help);
// -j, --progress, --force, --resume, -q.
// Whether a command offers --resume (a build written as a package does; an
// export, written afresh each time, does not).
enum class ResumeOption { kOffered, kNotOffered };
void declare_run_options(CliArgs& cli, BuildOptions& o,
                         ResumeOption resume = ResumeOption::kOffered);
// What identifies a build for --resume: the reproducible command line and
// each input's size and modification time.
std::string build_key(const BuildOptions& o);

// Parses; false after --help. Requires inputs and -o, checks --bbox and the
// zoom range; applies -q; records the command line under `program`.
bool parse_build_command(CliArgs& cli, BuildOptions& o, const std::vector<std::string>& args,
                         const std::string& program, const std::string& input_what);

}  // namespace globe
