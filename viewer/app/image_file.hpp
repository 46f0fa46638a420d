// Writing RGBA pixels as an RGB PNG (through the kit's libpng encoder), under
// a temporary name renamed on success so the final name never holds a
// partial image.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace globe::viewer {

// rgba: width*height*4 bytes, top row first. Throws OutputError.
void write_png(const std::string& path, const std::vector<uint8_t>& rgba, int width, int height);

}  // namespace globe::viewer
