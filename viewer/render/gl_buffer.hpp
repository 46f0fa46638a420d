// Refilling a shader storage buffer each frame, shared by the deferred
// passes: a fresh store (the driver orphans the old one if still in use),
// never empty (at least 16 bytes, so every binding is valid).
#pragma once

#include <algorithm>
#include <cstddef>

#include "platform/gl.hpp"

namespace globe::viewer {

inline void fill_buffer(GLuint buffer, size_t bytes, const void* data) {
  gl::NamedBufferData(buffer, std::max<size_t>(bytes, 16), nullptr, GL_STREAM_DRAW);
  if (bytes) gl::NamedBufferSubData(buffer, 0, bytes, data);
}

}  // namespace globe::viewer
