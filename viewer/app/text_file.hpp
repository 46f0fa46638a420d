// Writing a text file (the --labels-json record) under a temporary name
// renamed on success, so the final name never holds a partial file.
#pragma once

#include <string>

namespace globe::viewer {

// Throws OutputError naming the file.
void write_text_file(const std::string& path, const std::string& text);

}  // namespace globe::viewer
