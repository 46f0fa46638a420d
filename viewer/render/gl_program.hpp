// Compiling and linking GLSL programs, with the driver's log in the error.
#pragma once

#include <string>
#include <vector>

#include "platform/gl.hpp"

namespace globe::viewer {

class GlProgram {
 public:
  GlProgram() = default;
  // Throws std::runtime_error with the compile/link log. `feedback`: names of
  // vertex outputs captured by transform feedback (interleaved).
  GlProgram(const std::string& name, const std::string& vertex_src, const std::string& fragment_src,
            const std::vector<const char*>& feedback = {});
  // A compute program (same errors).
  static GlProgram compute(const std::string& name, const std::string& compute_src);
  ~GlProgram();
  GlProgram(GlProgram&& o) noexcept : id_(o.id_) { o.id_ = 0; }
  GlProgram& operator=(GlProgram&& o) noexcept;
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;

  GLuint id() const { return id_; }
  GLint uniform(const char* name) const { return gl::GetUniformLocation(id_, name); }

 private:
  GLuint id_ = 0;
};

}  // namespace globe::viewer
