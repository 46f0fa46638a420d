// Error categories of the command-line tools and their exit codes. Only
// main() turns these into messages and exit codes (docs/cli.md "Exit codes").
#pragma once

#include <stdexcept>
#include <string>

namespace globe {

enum ExitCode : int {
  kExitOk = 0,
  kExitDataError = 1,    // bad input data (missing, unreadable, no CRS, no data, corrupt package)
  kExitUsage = 2,        // bad command line
  kExitOutputError = 3,  // output cannot be written (exists, unwritable, disk full)
  kExitInternal = 4,     // a bug
  kExitWarnings = 5,     // validate: package usable but with warnings
  kExitBlankFrame = 6,   // globe-view: the frame shows no terrain (written all the same)
};

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace globe
