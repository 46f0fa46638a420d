// What a tool's `info`, `validate` and `extract` do for each package kind it
// reads: one KindInspection per kind, defined in the kind's own file
// (tools/tiler/inspect/terrain_inspect.cpp …) and listed in the tool's table
// (inspect/inspect_commands.cpp). The commands parse their arguments, find
// the package's row and call it; a kind the tool does not read is an error
// that names the tool that does (tileformat's descriptor).
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tileformat/package_kinds.hpp"

namespace globe {

// What `extract` was asked for (each tool parses the options it offers).
struct ExtractRequest {
  std::string package, output;
  int zoom = 0;
  std::optional<std::vector<double>> bbox;  // W,S,E,N (globe-tiler)
  std::string layer;                        // analysis packages: the layer to write
  bool force = false;
  bool quiet = false;
};

struct KindInspection {
  tileformat::PackageKind kind;
  // `info PACKAGE [--json]`: prints on stdout; returns the exit code.
  int (*info)(const std::string& path, bool json);
  // `validate PACKAGE`: a report on stdout; exit 0 valid, 5 warnings only, 1 errors.
  int (*validate)(const std::string& path);
  // `extract PACKAGE --zoom Z -o OUT`: returns the exit code.
  int (*extract)(const ExtractRequest& request);
};

// The row for the package at `path`. Throws InputError naming the file if it
// is not a package of ours, or if `table` has no row for its kind; then the
// message names `command` and the tool that reads the kind.
const KindInspection& inspection_for(const std::string& path,
                                     std::span<const KindInspection* const> table,
                                     const std::string& command);

// `TOOL info PACKAGE [--json]` and `TOOL validate PACKAGE` over a tool's
// table; `tool` is the program name ("globe-tiler"), `kinds` the help's
// list of kinds ("terrain, image or analysis").
int run_info_command(const std::string& tool, const std::string& kinds,
                     std::span<const KindInspection* const> table,
                     const std::vector<std::string>& args);
int run_validate_command(const std::string& tool, const std::string& kinds,
                         std::span<const KindInspection* const> table,
                         const std::vector<std::string>& args);

}  // namespace globe
