// The subcommands of globe-vectorize. Each parses its arguments (throwing
// UsageError), does its work and returns an exit code; only main() catches
// and reports errors.
#pragma once

#include <string>
#include <vector>

namespace globe {

int run_lines(const std::vector<std::string>& args);
int run_lines_info(const std::vector<std::string>& args);
int run_lines_validate(const std::vector<std::string>& args);
int run_lines_extract(const std::vector<std::string>& args);
int run_lines_merge(const std::vector<std::string>& args);
int run_points(const std::vector<std::string>& args);
int run_areas(const std::vector<std::string>& args);
int run_bundle(const std::vector<std::string>& args);
int run_export(const std::vector<std::string>& args);

}  // namespace globe
