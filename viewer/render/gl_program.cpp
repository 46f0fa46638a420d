// GLSL program building (see gl_program.hpp).
#include "render/gl_program.hpp"

#include <stdexcept>
#include <utility>

namespace globe::viewer {
namespace {

GLuint compile(const std::string& name, GLenum type, const std::string& src) {
  const GLuint s = gl::CreateShader(type);
  const char* text = src.c_str();
  gl::ShaderSource(s, 1, &text, nullptr);
  gl::CompileShader(s);
  GLint ok = 0;
  gl::GetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    gl::GetShaderInfoLog(s, sizeof log, nullptr, log);
    gl::DeleteShader(s);
    throw std::runtime_error(name + (type == GL_VERTEX_SHADER ? " vertex" : " fragment") +
                             " shader does not compile: " + log);
  }
  return s;
}

}  // namespace

GlProgram::GlProgram(const std::string& name, const std::string& vertex_src,
                     const std::string& fragment_src, const std::vector<const char*>& feedback) {
  const GLuint vs = compile(name, GL_VERTEX_SHADER, vertex_src);
  const GLuint fs = fragment_src.empty() ? 0 : compile(name, GL_FRAGMENT_SHADER, fragment_src);
  id_ = gl::CreateProgram();
  gl::AttachShader(id_, vs);
  if (fs) gl::AttachShader(id_, fs);
  if (!feedback.empty())
    gl::TransformFeedbackVaryings(id_, static_cast<GLsizei>(feedback.size()), feedback.data(),
                                  GL_INTERLEAVED_ATTRIBS);
  gl::LinkProgram(id_);
  gl::DeleteShader(vs);
  if (fs) gl::DeleteShader(fs);
  GLint ok = 0;
  gl::GetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    gl::GetProgramInfoLog(id_, sizeof log, nullptr, log);
    gl::DeleteProgram(id_);
    id_ = 0;
    throw std::runtime_error(name + " program does not link: " + log);
  }
}

GlProgram::~GlProgram() {
  if (id_) gl::DeleteProgram(id_);
}

GlProgram& GlProgram::operator=(GlProgram&& o) noexcept {
  std::swap(id_, o.id_);
  return *this;
}

}  // namespace globe::viewer
