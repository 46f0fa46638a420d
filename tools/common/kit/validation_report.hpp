// What `validate` commands found: errors and warnings printed on stdout (the
// first 50 of each), counted, and turned into the exit code (docs/cli.md).
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>

#include "runtime/errors.hpp"

namespace globe {

struct ValidationReport {
  uint64_t errors = 0, warnings = 0;
  void error(const std::string& m) {
    if (errors++ < 50) std::printf("error: %s\n", m.c_str());
  }
  void warning(const std::string& m) {
    if (warnings++ < 50) std::printf("warning: %s\n", m.c_str());
  }
  // 1 with errors, 5 with warnings only, else 0.
  int exit_code() const { return errors ? kExitDataError : warnings ? kExitWarnings : kExitOk; }
};

}  // namespace globe
