// Offscreen OpenGL 4.5 core contexts for headless rendering (snapshots,
// stats, mesh export, tests). The renderer draws into its own framebuffer
// object, so a context only has to exist and be current:
//  - OSMesa: Mesa's software rasterizer, needs no display or GPU (default);
//  - EGL surfaceless (EGL_MESA_platform_surfaceless), for GPU servers and for
//    Mesa >= 25.1, which dropped OSMesa.
#pragma once

#include <memory>
#include <string>

namespace globe::viewer {

class HeadlessContext {
 public:
  virtual ~HeadlessContext() = default;
  virtual std::string platform() const = 0;  // "osmesa" or "egl"
};

// platform: "osmesa", "egl" or "auto" (OSMesa, then EGL). The context is
// current on the calling thread and the GL functions are loaded. Throws
// std::runtime_error saying what is missing.
std::unique_ptr<HeadlessContext> create_headless_context(const std::string& platform);

}  // namespace globe::viewer
