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
    const char* kind = type == GL_VERTEX_SHADER    ? " vertex"
                       : type == GL_COMPUTE_SHADER ? " compute"
                                                   : " fragment";
    throw std::runtime_error(name + kind + " shader does not compile: " + log);
  }
  return s;
}

// Links `shaders` (deleted after) into a program; throws with the log.
GLuint link(const std::string& name, const std::vector<GLuint>& shaders,
            const std::vector<const char*>& feedback) {
  const GLuint id = gl::CreateProgram();
  for (GLuint s : shaders)
    gl::AttachShader(id, s);
  if (!feedback.empty())
    gl::TransformFeedbackVaryings(id, static_cast<GLsizei>(feedback.size()), feedback.data(),
                                  GL_INTERLEAVED_ATTRIBS);
  gl::LinkProgram(id);
  for (GLuint s : shaders)
    gl::DeleteShader(s);
  GLint ok = 0;
  gl::GetProgramiv(id, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    gl::GetProgramInfoLog(id, sizeof log, nullptr, log);
    gl::DeleteProgram(id);
    throw std::runtime_error(name + " program does not link: " + log);
  }
  return id;
}

}  // namespace

GlProgram::GlProgram(const std::string& name, const std::string& vertex_src,
                     const std::string& fragment_src, const std::vector<const char*>& feedback) {
  std::vector<GLuint> shaders{compile(name, GL_VERTEX_SHADER, vertex_src)};
  if (!fragment_src.empty()) shaders.push_back(compile(name, GL_FRAGMENT_SHADER, fragment_src));
  id_ = link(name, shaders, feedback);
}

GlProgram GlProgram::compute(const std::string& name, const std::string& compute_src) {
  GlProgram p;
  p.id_ = link(name, {compile(name, GL_COMPUTE_SHADER, compute_src)}, {});
  return p;
}

GlProgram::~GlProgram() {
  if (id_) gl::DeleteProgram(id_);
}

GlProgram& GlProgram::operator=(GlProgram&& o) noexcept {
  std::swap(id_, o.id_);
  return *this;
}

}  // namespace globe::viewer
