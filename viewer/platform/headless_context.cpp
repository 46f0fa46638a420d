// OSMesa and EGL surfaceless contexts (see headless_context.hpp). The two C
// APIs are wrapped here and nowhere else.
#include "platform/headless_context.hpp"

// gl.hpp (glcorearb.h) first: osmesa.h pulls in GL/gl.h, which would hide
// glcorearb.h's OpenGL 1.x function-pointer types.
#include "platform/gl.hpp"
// clang-format off
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/osmesa.h>
// clang-format on

#include <stdexcept>
#include <vector>

namespace globe::viewer {
namespace {

class OsMesaContext final : public HeadlessContext {
 public:
  OsMesaContext() {
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           0,
                           OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION,
                           4,
                           OSMESA_CONTEXT_MINOR_VERSION,
                           5,
                           0};
    ctx_ = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!ctx_) throw std::runtime_error("OSMesa: cannot create an OpenGL 4.5 core context");
    // The renderer draws into its own framebuffer; OSMesa still wants a
    // buffer to make the context current.
    buffer_.resize(4);
    if (!OSMesaMakeCurrent(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, 1, 1)) {
      OSMesaDestroyContext(ctx_);
      throw std::runtime_error("OSMesa: cannot make the context current");
    }
    gl::load([](const char* name) { return reinterpret_cast<void*>(OSMesaGetProcAddress(name)); });
  }
  ~OsMesaContext() override { OSMesaDestroyContext(ctx_); }
  std::string platform() const override { return "osmesa"; }

 private:
  OSMesaContext ctx_ = nullptr;
  std::vector<unsigned char> buffer_;
};

class EglContext final : public HeadlessContext {
 public:
  EglContext() {
    auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (get_platform_display)
      dpy_ = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (dpy_ == EGL_NO_DISPLAY) dpy_ = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (dpy_ == EGL_NO_DISPLAY) throw std::runtime_error("EGL: no display");
    EGLint major = 0, minor = 0;
    if (!eglInitialize(dpy_, &major, &minor)) throw std::runtime_error(fail("eglInitialize"));
    if (!eglBindAPI(EGL_OPENGL_API)) throw std::runtime_error(fail("eglBindAPI(OpenGL)"));
    const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                     EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!eglChooseConfig(dpy_, config_attribs, &config, 1, &count) || count == 0)
      throw std::runtime_error(fail("eglChooseConfig"));
    const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                  4,
                                  EGL_CONTEXT_MINOR_VERSION,
                                  5,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                  EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                  EGL_NONE};
    ctx_ = eglCreateContext(dpy_, config, EGL_NO_CONTEXT, ctx_attribs);
    if (ctx_ == EGL_NO_CONTEXT) throw std::runtime_error(fail("eglCreateContext(4.5 core)"));
    if (!eglMakeCurrent(dpy_, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx_))
      throw std::runtime_error(fail("eglMakeCurrent (surfaceless)"));
    gl::load([](const char* name) { return reinterpret_cast<void*>(eglGetProcAddress(name)); });
  }
  ~EglContext() override {
    if (dpy_ != EGL_NO_DISPLAY) {
      eglMakeCurrent(dpy_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (ctx_ != EGL_NO_CONTEXT) eglDestroyContext(dpy_, ctx_);
      eglTerminate(dpy_);
    }
  }
  std::string platform() const override { return "egl"; }

 private:
  std::string fail(const char* what) const {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", eglGetError());
    return std::string("EGL: ") + what + " failed (" + code + ")";
  }
  EGLDisplay dpy_ = EGL_NO_DISPLAY;
  EGLContext ctx_ = EGL_NO_CONTEXT;
};

}  // namespace

std::unique_ptr<HeadlessContext> create_headless_context(const std::string& platform) {
  if (platform == "osmesa") return std::make_unique<OsMesaContext>();
  if (platform == "egl") return std::make_unique<EglContext>();
  if (platform != "auto") throw std::runtime_error("unknown headless platform '" + platform + "'");
  try {
    return std::make_unique<OsMesaContext>();
  } catch (const std::exception& osmesa) {
    try {
      return std::make_unique<EglContext>();
    } catch (const std::exception& egl) {
      throw std::runtime_error(std::string("no headless OpenGL 4.5 context: ") + osmesa.what() +
                               "; " + egl.what());
    }
  }
}

}  // namespace globe::viewer
