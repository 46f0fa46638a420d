// Subcommand dispatch (see command_tool.hpp).
#include "kit/command_tool.hpp"

#include <cstdio>

#include "runtime/error_report.hpp"
#include "runtime/errors.hpp"

namespace globe {

int run_command_tool(const std::string& program, const std::string& version, const char* usage,
                     const std::vector<ToolCommand>& commands, int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) {
    std::fputs(usage, stderr);
    return kExitUsage;
  }
  const std::string command = args[0];
  args.erase(args.begin());
  return run_reporting_errors(program, program + " " + command, "", [&]() -> int {
    for (const ToolCommand& c : commands)
      if (c.name == command) return c.run(args);
    if (command == "-h" || command == "--help" || command == "help") {
      std::fputs(usage, stdout);
      return kExitOk;
    }
    if (command == "--version") {
      std::printf("%s %s\n", program.c_str(), version.c_str());
      return kExitOk;
    }
    std::fprintf(stderr, "%s: unknown command '%s'\n\n%s", program.c_str(), command.c_str(), usage);
    return kExitUsage;
  });
}

}  // namespace globe
