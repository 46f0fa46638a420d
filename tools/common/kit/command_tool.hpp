// main() of a tool made of subcommands (`globe-tiler terrain ...`): picks the
// command, handles --help / --version / unknown commands, and maps errors to
// messages and exit codes through run_reporting_errors.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace globe {

struct ToolCommand {
  std::string name;
  std::function<int(const std::vector<std::string>& args)> run;
};

int run_command_tool(const std::string& program, const std::string& version, const char* usage,
                     const std::vector<ToolCommand>& commands, int argc, char** argv);

}  // namespace globe
