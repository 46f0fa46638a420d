// Flat 2D drawing over a finished image: filled rectangles and text in the
// 5 x 7 bitmap font (bitmap_font.hpp), in pixel coordinates from the top-left
// corner, alpha-blended. Used for legends; queue shapes, then draw() them
// into a framebuffer in one call.
#pragma once

#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "render/gl_program.hpp"

namespace globe::viewer {

class TextOverlay {
 public:
  TextOverlay();
  ~TextOverlay();
  TextOverlay(const TextOverlay&) = delete;
  TextOverlay& operator=(const TextOverlay&) = delete;

  void rect(float x, float y, float w, float h, glm::vec4 rgba);
  // Text with its top-left corner at (x, y), each font pixel `scale` pixels;
  // characters outside printable ASCII show as '?'.
  void text(float x, float y, const std::string& s, glm::vec4 rgba, int scale = 2);
  static float text_width(const std::string& s, int scale = 2) {
    return float(s.size()) * float(6 * scale);
  }
  static float text_height(int scale = 2) { return float(7 * scale); }
  // Draws everything queued into `fbo` (width x height) and clears the queue.
  void draw(GLuint fbo, int width, int height);

 private:
  struct Vertex {
    float x, y, u, v;  // u < 0: solid
    float r, g, b, a;
  };
  void quad(float x0, float y0, float x1, float y1, float u0, float v0, float u1, float v1,
            glm::vec4 rgba);
  GlProgram program_;
  GLuint font_ = 0, vao_ = 0, vbo_ = 0;
  std::vector<Vertex> vertices_;
};

}  // namespace globe::viewer
