// info and validate over a tool's table of kinds (see kind_inspection.hpp).
#include "kit/kind_inspection.hpp"

#include "runtime/cli_args.hpp"
#include "runtime/errors.hpp"
#include "runtime/package_open.hpp"

namespace globe {

const KindInspection& inspection_for(const std::string& path,
                                     std::span<const KindInspection* const> table,
                                     const std::string& command) {
  const std::string format = package_format(*open_package(path), path);
  const std::optional<tileformat::PackageKind> kind = tileformat::package_kind_of_format(format);
  if (!kind)
    throw InputError(path + ": a package of format '" + format + "', not made by these tools");
  for (const KindInspection* row : table)
    if (row->kind == *kind) return *row;
  const tileformat::PackageKindDescriptor& d = tileformat::describe(*kind);
  const std::string verb = command.substr(command.rfind(' ') + 1);
  throw InputError(path + ": " + a_package_of(*kind) + ", which " + command +
                   " does not read; run " + d.tool + " " + verb + " " + path);
}

int run_info_command(const std::string& tool, const std::string& kinds,
                     std::span<const KindInspection* const> table,
                     const std::vector<std::string>& args) {
  bool json = false;
  const std::string command = tool + " info";
  CliArgs cli(command, command + " PACKAGE [--json]\n\nPrints a " + kinds +
                           " package's metadata, zoom range, tile counts and sizes, and what "
                           "its kind adds.");
  cli.flag("--json", "one JSON object on stdout instead (docs/cli.md \"info --json\")",
           [&] { json = true; });
  auto positional = cli.parse_command(args, 1, 1, "PACKAGE");
  if (!positional) return kExitOk;
  const std::string& path = (*positional)[0];
  return inspection_for(path, table, command).info(path, json);
}

int run_validate_command(const std::string& tool, const std::string& kinds,
                         std::span<const KindInspection* const> table,
                         const std::vector<std::string>& args) {
  const std::string command = tool + " validate";
  CliArgs cli(command, command + " PACKAGE\n\nDecodes every tile of a " + kinds +
                           " package and checks its schema and invariants.\n"
                           "Exit 0: valid; 5: warnings only; 1: errors.");
  auto positional = cli.parse_command(args, 1, 1, "PACKAGE");
  if (!positional) return kExitOk;
  const std::string& path = (*positional)[0];
  return inspection_for(path, table, command).validate(path);
}

}  // namespace globe
