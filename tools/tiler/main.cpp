// globe-tiler: DEMs -> terrain packages, imagery -> image packages, terrain
// analytics, and tools to inspect them.
//
// This executable links no GDAL. Loading GDAL and the hundred libraries it
// needs costs about 0.1 CPU s at every start (on the CI machines), as much as
// analyzing a 513^2 DEM; `analyze` reads and writes packages only, so it runs
// here (as do --help and --version; `export --watermask` reads polygons with
// OGR and does not). Every other command runs in
// globe-tiler-gdal, the executable next to this one: exec'd in this process
// with the same arguments, so its pid, signals, output and exit code are the
// command's own (docs/architecture.md).
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "kit/command_tool.hpp"
#include "kit/heap_tuning.hpp"
#include "runtime/errors.hpp"
#include "tiler_commands.hpp"

namespace {

// Replaces this process by globe-tiler-gdal with the same arguments; returns
// only when that fails.
int run_in_gdal_executable(int argc, char** argv) {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::string gdal = (self.parent_path() / "globe-tiler-gdal").string();
  std::vector<char*> args(argv, argv + argc);
  args.push_back(nullptr);
  ::execv(gdal.c_str(), args.data());
  std::fprintf(stderr,
               "globe-tiler: cannot run %s for '%s': %s; it is built and installed with "
               "globe-tiler (scripts/build.sh builds both)\n",
               gdal.c_str(), argv[1], std::strerror(errno));
  return globe::kExitInternal;
}

bool runs_here(const std::string& command) {
  for (const char* c : {"analyze", "export", "-h", "--help", "help", "--version"})
    if (command == c) return true;
  return false;
}

}  // namespace

// `export --watermask` reads polygons with OGR.
bool needs_gdal(int argc, char** argv) {
  for (int i = 2; i < argc; ++i)
    if (std::string(argv[i]).rfind("--watermask", 0) == 0) return true;
  return false;
}

int main(int argc, char** argv) {
  if (argc > 1 && (!runs_here(argv[1]) || needs_gdal(argc, argv)))
    return run_in_gdal_executable(argc, argv);
  globe::keep_tile_buffers_in_heap();
  return globe::run_command_tool("globe-tiler", GLOBE_VERSION, globe::kTilerUsage,
                                 {{"analyze", globe::run_analyze}, {"export", globe::run_export}},
                                 argc, argv);
}
