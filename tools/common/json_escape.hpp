// Escaping text for JSON string values (progress lines, metadata JSON).
#pragma once

#include <string>

namespace globe {

// Escapes quotes and backslashes; control characters become \u00XX.
std::string json_escape(const std::string& s);

}  // namespace globe
