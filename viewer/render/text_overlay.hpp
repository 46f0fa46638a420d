// Flat 2D drawing over a finished image: filled rectangles and text in
// signed-distance-field glyphs of Debian's fonts (data/text_engine.hpp: the
// same shaping and atlas as the labels), in pixel coordinates from the
// top-left corner, alpha-blended. Used for legends; queue shapes, then
// draw() them into a framebuffer in one call.
#pragma once

#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "data/text_engine.hpp"
#include "render/gl_program.hpp"

namespace globe::viewer {

class TextOverlay {
 public:
  TextOverlay();
  ~TextOverlay();
  TextOverlay(const TextOverlay&) = delete;
  TextOverlay& operator=(const TextOverlay&) = delete;

  void rect(float x, float y, float w, float h, glm::vec4 rgba);
  // Text in a row of text_height(scale) pixels whose top-left corner is
  // (x, y): capitals fill it, descenders reach a little below; scale 1 is
  // 9 px text (any script Debian's fonts cover, shaped by HarfBuzz).
  void text(float x, float y, const std::string& s, glm::vec4 rgba, int scale = 2);
  // The advance width of `s` at `scale`, pixels.
  float text_width(const std::string& s, int scale = 2);
  static float text_height(int scale = 2) { return float(7 * scale); }
  // Draws everything queued into `fbo` (width x height) and clears the queue.
  void draw(GLuint fbo, int width, int height);
  // The rectangle (x0, y0, x1, y1) the last draw() covered (all zero when it
  // drew nothing): what labels keep clear of.
  const glm::vec4& drawn_bounds() const { return drawn_; }

 private:
  struct Vertex {
    float x, y, u, v;  // u < 0: solid
    float r, g, b, a;
  };
  static float size_px(int scale) { return 9.0f * float(scale); }
  void quad(float x0, float y0, float x1, float y1, float u0, float v0, float u1, float v1,
            glm::vec4 rgba);
  TextEngine* engine_;  // nullptr: no fonts, no text
  GlProgram program_;
  GLuint atlas_ = 0, vao_ = 0, vbo_ = 0;
  size_t uploaded_glyphs_ = 0;  // the atlas's glyphs when last uploaded
  std::vector<Vertex> vertices_;
  glm::vec4 drawn_{0, 0, 0, 0};
};

}  // namespace globe::viewer
