// Run-time loading of the OpenGL function list (see gl.hpp).
#include "platform/gl.hpp"

#include <cstdio>
#include <stdexcept>

namespace gl {

void load(GetProc get_proc) {
  std::string missing;
#define GLOBE_GL_LOAD(type, name)                      \
  name = reinterpret_cast<type>(get_proc("gl" #name)); \
  if (!name) missing += std::string(missing.empty() ? "" : ", ") + "gl" #name;
  GLOBE_GL_FUNCTIONS(GLOBE_GL_LOAD)
#undef GLOBE_GL_LOAD
  if (!missing.empty())
    throw std::runtime_error("the OpenGL context lacks " + missing + " (OpenGL 4.5 core needed)");
  GLint major = 0, minor = 0;
  GetIntegerv(GL_MAJOR_VERSION, &major);
  GetIntegerv(GL_MINOR_VERSION, &minor);
  if (major < 4 || (major == 4 && minor < 5))
    throw std::runtime_error("OpenGL " + std::to_string(major) + "." + std::to_string(minor) +
                             " context; the viewer needs OpenGL 4.5 core");
}

std::string describe_context() {
  auto str = [](GLenum e) {
    const GLubyte* s = GetString(e);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  return "OpenGL " + str(GL_VERSION) + " / " + str(GL_RENDERER);
}

void check(const char* what) {
  const GLenum e = GetError();
  if (e == GL_NO_ERROR) return;
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", e);
  throw std::runtime_error(std::string(what) + ": GL error " + code);
}

}  // namespace gl
