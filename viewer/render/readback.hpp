// Getting a rendered image out of an offscreen framebuffer: back to the CPU
// (snapshots) or onto the window.
#pragma once

#include <cstdint>
#include <vector>

#include "platform/gl.hpp"

namespace globe::viewer {

// Colour attachment 0 of `fbo` as RGBA8, top row first.
std::vector<uint8_t> read_rgba(GLuint fbo, int width, int height);
// Scales colour attachment 0 of `fbo` onto the window's framebuffer (0).
void blit_to_window(GLuint fbo, int width, int height, int window_width, int window_height);

}  // namespace globe::viewer
