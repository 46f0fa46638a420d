// The package-kind-specific halves of `globe-vectorize info`, `validate` and
// `extract` (inspect_commands.cpp calls them through its table of kinds):
// line-cluster packages in lines_inspect.cpp, point packages in
// points_inspect.cpp. The signatures are KindInspection's.
#pragma once

#include <string>

#include "kit/kind_inspection.hpp"

namespace globe {

int lines_info(const std::string& path, bool json);
int lines_validate(const std::string& path);
int lines_extract(const ExtractRequest& request);
int points_info(const std::string& path, bool json);
int points_validate(const std::string& path);
int points_extract(const ExtractRequest& request);

}  // namespace globe
