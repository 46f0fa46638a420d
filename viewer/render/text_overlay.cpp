// 2D overlay (see text_overlay.hpp).
#include "render/text_overlay.hpp"

#include "render/bitmap_font.hpp"

namespace globe::viewer {

namespace {

// The font as a texture: glyphs side by side, each cell kGlyphWidth x
// kGlyphHeight texels (255 = ink).
constexpr int kAtlasWidth = kGlyphWidth * static_cast<int>(kGlyphs.size());

constexpr const char* kVertex = R"(#version 450 core
layout(location = 0) in vec4 a_pos_uv;
layout(location = 1) in vec4 a_color;
uniform vec2 u_viewport;
out vec2 v_uv;
out vec4 v_color;
void main() {
  v_uv = a_pos_uv.zw;
  v_color = a_color;
  vec2 ndc = a_pos_uv.xy / u_viewport * 2.0 - 1.0;
  gl_Position = vec4(ndc.x, -ndc.y, 0.0, 1.0);
}
)";

constexpr const char* kFragment = R"(#version 450 core
in vec2 v_uv;
in vec4 v_color;
uniform sampler2D u_font;
out vec4 o_color;
void main() {
  float ink = v_uv.x < 0.0 ? 1.0 : texture(u_font, v_uv).r;
  if (ink < 0.5) discard;
  o_color = v_color;
}
)";

}  // namespace

TextOverlay::TextOverlay() {
  program_ = GlProgram("text overlay", kVertex, kFragment);
  std::vector<uint8_t> texels(size_t(kAtlasWidth) * kGlyphHeight, 0);
  for (size_t g = 0; g < kGlyphs.size(); ++g)
    for (int row = 0; row < kGlyphHeight; ++row)
      for (int col = 0; col < kGlyphWidth; ++col)
        if (kGlyphs[g][row] >> (kGlyphWidth - 1 - col) & 1)
          texels[size_t(row) * kAtlasWidth + g * kGlyphWidth + col] = 255;
  gl::CreateTextures(GL_TEXTURE_2D, 1, &font_);
  gl::TextureStorage2D(font_, 1, GL_R8, kAtlasWidth, kGlyphHeight);
  gl::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl::TextureSubImage2D(font_, 0, 0, 0, kAtlasWidth, kGlyphHeight, GL_RED, GL_UNSIGNED_BYTE,
                        texels.data());
  gl::TextureParameteri(font_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl::TextureParameteri(font_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl::CreateBuffers(1, &vbo_);
  gl::CreateVertexArrays(1, &vao_);
  gl::VertexArrayVertexBuffer(vao_, 0, vbo_, 0, sizeof(Vertex));
  for (GLuint a = 0; a < 2; ++a) {
    gl::EnableVertexArrayAttrib(vao_, a);
    gl::VertexArrayAttribFormat(vao_, a, 4, GL_FLOAT, GL_FALSE, a * 4 * sizeof(float));
    gl::VertexArrayAttribBinding(vao_, a, 0);
  }
  gl::check("creating the text overlay");
}

TextOverlay::~TextOverlay() {
  gl::DeleteTextures(1, &font_);
  gl::DeleteBuffers(1, &vbo_);
  gl::DeleteVertexArrays(1, &vao_);
}

void TextOverlay::quad(float x0, float y0, float x1, float y1, float u0, float v0, float u1,
                       float v1, glm::vec4 c) {
  const Vertex a{x0, y0, u0, v0, c.r, c.g, c.b, c.a}, b{x1, y0, u1, v0, c.r, c.g, c.b, c.a},
      d{x0, y1, u0, v1, c.r, c.g, c.b, c.a}, e{x1, y1, u1, v1, c.r, c.g, c.b, c.a};
  vertices_.insert(vertices_.end(), {a, b, d, d, b, e});
}

void TextOverlay::rect(float x, float y, float w, float h, glm::vec4 rgba) {
  quad(x, y, x + w, y + h, -1, -1, -1, -1, rgba);
}

void TextOverlay::text(float x, float y, const std::string& s, glm::vec4 rgba, int scale) {
  const float cw = float(kGlyphWidth * scale), ch = float(kGlyphHeight * scale);
  for (char c : s) {
    const int g = (c >= kFirstGlyph && c <= kLastGlyph ? c : '?') - kFirstGlyph;
    const float u0 = float(g * kGlyphWidth) / kAtlasWidth,
                u1 = float((g + 1) * kGlyphWidth) / kAtlasWidth;
    if (c != ' ') quad(x, y, x + cw, y + ch, u0, 0, u1, 1, rgba);
    x += float((kGlyphWidth + 1) * scale);
  }
}

void TextOverlay::draw(GLuint fbo, int width, int height) {
  if (vertices_.empty()) return;
  gl::NamedBufferData(vbo_, vertices_.size() * sizeof(Vertex), vertices_.data(), GL_STREAM_DRAW);
  gl::BindFramebuffer(GL_FRAMEBUFFER, fbo);
  gl::Viewport(0, 0, width, height);
  gl::Disable(GL_DEPTH_TEST);
  gl::Enable(GL_BLEND);
  gl::BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  gl::UseProgram(program_.id());
  gl::Uniform2f(program_.uniform("u_viewport"), float(width), float(height));
  gl::Uniform1i(program_.uniform("u_font"), 0);
  gl::BindTextureUnit(0, font_);
  gl::BindVertexArray(vao_);
  gl::DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices_.size()));
  gl::BindVertexArray(0);
  gl::Disable(GL_BLEND);
  gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
  vertices_.clear();
  gl::check("drawing the overlay");
}

}  // namespace globe::viewer
