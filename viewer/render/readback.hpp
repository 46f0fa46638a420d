// Getting a rendered image out of an offscreen framebuffer: back to the CPU
// (snapshots) or onto the window.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "platform/gl.hpp"

namespace globe::viewer {

// Colour attachment 0 of `fbo` as RGBA8, top row first.
std::vector<uint8_t> read_rgba(GLuint fbo, int width, int height);
// The world point (w = 1) the terrain pass wrote at pixel (x, y) of the
// G-buffer, y counted from the top; w = 0 where no terrain is.
glm::vec4 read_position(GLuint gbuffer_fbo, int x, int y, int height);
// The fraction of the G-buffer's pixels where the terrain (or the globe's
// polar caps) was drawn: position w = 1.
double ground_fraction(GLuint gbuffer_fbo, int width, int height);
// The RGBA32F value of colour attachment `attachment` of `fbo` at pixel
// (x, y), y counted from the top.
glm::vec4 read_rgba32f(GLuint fbo, int attachment, int x, int y, int height);
// The R32UI value of colour attachment `attachment` (0-based) of `fbo` at
// pixel (x, y), y counted from the top.
uint32_t read_u32(GLuint fbo, int attachment, int x, int y, int height);
// The rectangle (x, y, w, h) of a float colour attachment (GL rows, from the
// bottom), red channel.
std::vector<float> read_r32f(GLuint fbo, int attachment, int x, int y, int w, int h);
// Scales colour attachment 0 of `fbo` onto the window's framebuffer (0).
void blit_to_window(GLuint fbo, int width, int height, int window_width, int window_height);

}  // namespace globe::viewer
