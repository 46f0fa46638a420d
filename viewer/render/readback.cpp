// Image readback (see readback.hpp).
#include "render/readback.hpp"

#include <cstring>
#include <vector>

namespace globe::viewer {

namespace {

// Reads the rectangle (x, y, w, h) of colour attachment `attachment` of `fbo`
// (GL rows, from the bottom) into `out`; attachment 0 stays the read buffer.
void read_attachment(GLuint fbo, int attachment, int x, int y, int w, int h, GLenum format,
                     GLenum type, void* out, const char* what) {
  gl::NamedFramebufferReadBuffer(fbo, GL_COLOR_ATTACHMENT0 + attachment);
  gl::BindFramebuffer(GL_FRAMEBUFFER, fbo);
  gl::PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl::ReadPixels(x, y, w, h, format, type, out);
  gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl::NamedFramebufferReadBuffer(fbo, GL_COLOR_ATTACHMENT0);
  gl::check(what);
}

}  // namespace

std::vector<uint8_t> read_rgba(GLuint fbo, int width, int height) {
  std::vector<uint8_t> rgba(size_t(width) * height * 4);
  read_attachment(fbo, 0, 0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data(),
                  "reading the image back");
  // GL rows are bottom-up.
  const size_t row = size_t(width) * 4;
  std::vector<uint8_t> flipped(rgba.size());
  for (int y = 0; y < height; ++y)
    std::memcpy(&flipped[size_t(y) * row], &rgba[size_t(height - 1 - y) * row], row);
  return flipped;
}

glm::vec4 read_rgba32f(GLuint fbo, int attachment, int x, int y, int height) {
  glm::vec4 p(0);
  read_attachment(fbo, attachment, x, height - 1 - y, 1, 1, GL_RGBA, GL_FLOAT, &p,
                  "reading a G-buffer value");
  return p;
}

glm::vec4 read_position(GLuint fbo, int x, int y, int height) {
  return read_rgba32f(fbo, 1, x, y, height);
}

double ground_fraction(GLuint fbo, int width, int height) {
  std::vector<float> p(size_t(width) * height * 4);
  read_attachment(fbo, 1, 0, 0, width, height, GL_RGBA, GL_FLOAT, p.data(),
                  "reading the G-buffer's positions");
  size_t ground = 0;
  for (size_t i = 3; i < p.size(); i += 4)
    ground += p[i] > 0.5f;
  return p.empty() ? 0 : double(ground) / double(width * height);
}

uint32_t read_u32(GLuint fbo, int attachment, int x, int y, int height) {
  uint32_t v = 0;
  read_attachment(fbo, attachment, x, height - 1 - y, 1, 1, GL_RED_INTEGER, GL_UNSIGNED_INT, &v,
                  "reading a pick id");
  return v;
}

std::vector<float> read_r32f(GLuint fbo, int attachment, int x, int y, int w, int h) {
  std::vector<float> v(size_t(w) * h);
  read_attachment(fbo, attachment, x, y, w, h, GL_RED, GL_FLOAT, v.data(), "reading a float image");
  return v;
}

void blit_to_window(GLuint fbo, int width, int height, int window_width, int window_height) {
  gl::NamedFramebufferReadBuffer(fbo, GL_COLOR_ATTACHMENT0);
  gl::BlitNamedFramebuffer(fbo, 0, 0, 0, width, height, 0, 0, window_width, window_height,
                           GL_COLOR_BUFFER_BIT, GL_LINEAR);
}

}  // namespace globe::viewer
