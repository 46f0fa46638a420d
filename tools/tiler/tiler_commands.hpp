// The subcommands of globe-tiler. Each parses its arguments (throwing
// UsageError), does its work and returns an exit code; only main() catches
// and reports errors.
#pragma once

#include <string>
#include <vector>

namespace globe {

// The usage text of `globe-tiler` (tiler_usage.cpp), printed by both of its
// executables (main.cpp says why there are two).
extern const char* const kTilerUsage;

int run_terrain(const std::vector<std::string>& args);
int run_imagery(const std::vector<std::string>& args);
int run_analyze(const std::vector<std::string>& args);
int run_merge(const std::vector<std::string>& args);
int run_info(const std::vector<std::string>& args);
int run_validate(const std::vector<std::string>& args);
int run_extract(const std::vector<std::string>& args);
int run_export(const std::vector<std::string>& args);

}  // namespace globe
