// "#rrggbb" colours (style files, package metadata) as the floats shaders take.
#pragma once

#include <string>

#include <glm/vec4.hpp>

namespace globe::viewer {

// Opaque RGBA from "#rrggbb"; transparent black for anything else.
inline glm::vec4 hex_rgba(const std::string& hex) {
  if (hex.size() != 7 || hex[0] != '#') return glm::vec4(0);
  unsigned v = 0;
  for (size_t i = 1; i < 7; ++i) {
    const char c = hex[i];
    const unsigned d = c >= '0' && c <= '9'   ? unsigned(c - '0')
                       : c >= 'a' && c <= 'f' ? unsigned(c - 'a' + 10)
                       : c >= 'A' && c <= 'F' ? unsigned(c - 'A' + 10)
                                              : 16u;
    if (d > 15) return glm::vec4(0);
    v = v * 16 + d;
  }
  return {((v >> 16) & 255) / 255.0f, ((v >> 8) & 255) / 255.0f, (v & 255) / 255.0f, 1.0f};
}

}  // namespace globe::viewer
