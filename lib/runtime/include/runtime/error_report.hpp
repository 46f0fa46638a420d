// The one mapping from thrown errors to a stderr message and an exit code
// (docs/cli.md "Exit codes"), shared by every tool's main().
#pragma once

#include <functional>
#include <string>

namespace globe {

// Runs `body` and returns its exit code; if it throws, prints
// "<program>: <message>" (usage errors: "<usage_prefix>: <message><usage_suffix>")
// and returns the code of the error's category.
int run_reporting_errors(const std::string& program, const std::string& usage_prefix,
                         const std::string& usage_suffix, const std::function<int()>& body);

}  // namespace globe
