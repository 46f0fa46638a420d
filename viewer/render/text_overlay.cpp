// 2D overlay (see text_overlay.hpp).
#include "render/text_overlay.hpp"

#include <algorithm>

namespace globe::viewer {

namespace {

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

// MapLibre's SDF convention: the outline at 0.75.
constexpr const char* kFragment = R"(#version 450 core
in vec2 v_uv;
in vec4 v_color;
uniform sampler2D u_atlas;
out vec4 o_color;
void main() {
  float ink = 1.0;
  if (v_uv.x >= 0.0) {
    float d = texture(u_atlas, v_uv).r;
    float aa = max(fwidth(d) * 0.7, 1e-3);
    ink = smoothstep(0.75 - aa, 0.75 + aa, d);
  }
  if (ink <= 0.0) discard;
  o_color = vec4(v_color.rgb, v_color.a * ink);
}
)";

}  // namespace

TextOverlay::TextOverlay() : engine_(default_text_engine()) {
  program_ = GlProgram("text overlay", kVertex, kFragment);
  gl::CreateTextures(GL_TEXTURE_2D, 1, &atlas_);
  gl::TextureStorage2D(atlas_, 1, GL_R8, engine_ ? engine_->atlas().width() : 1,
                       engine_ ? engine_->atlas().height() : 1);
  gl::TextureParameteri(atlas_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl::TextureParameteri(atlas_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl::TextureParameteri(atlas_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl::TextureParameteri(atlas_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  uploaded_glyphs_ = size_t(-1);
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
  gl::DeleteTextures(1, &atlas_);
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

float TextOverlay::text_width(const std::string& s, int scale) {
  if (!engine_) return 0;
  return engine_->shape(s).width * size_px(scale) / TextEngine::kAtlasPx;
}

void TextOverlay::text(float x, float y, const std::string& s, glm::vec4 rgba, int scale) {
  if (!engine_) return;
  const ShapedString shaped = engine_->shape(s);
  const float k = size_px(scale) / TextEngine::kAtlasPx;
  const float baseline = y + text_height(scale);
  const text::GlyphAtlas& a = engine_->atlas();
  const float aw = float(a.width()), ah = float(a.height());
  for (const ShapedGlyph& g : shaped.glyphs) {
    if (!g.atlas) continue;
    const text::GlyphAtlas::Entry& e = *g.atlas;
    const float x0 = x + (g.x + float(e.left)) * k, y0 = baseline - (g.y + float(e.top)) * k;
    quad(x0, y0, x0 + float(e.width) * k, y0 + float(e.height) * k, float(e.x) / aw,
         float(e.y) / ah, float(e.x + e.width) / aw, float(e.y + e.height) / ah, rgba);
  }
}

void TextOverlay::draw(GLuint fbo, int width, int height) {
  drawn_ = {0, 0, 0, 0};
  if (vertices_.empty()) return;
  drawn_ = {vertices_[0].x, vertices_[0].y, vertices_[0].x, vertices_[0].y};
  for (const Vertex& v : vertices_)
    drawn_ = {std::min(drawn_.x, v.x), std::min(drawn_.y, v.y), std::max(drawn_.z, v.x),
              std::max(drawn_.w, v.y)};
  if (engine_ && engine_->atlas().glyph_count() != uploaded_glyphs_) {
    // Glyphs added since (by any user of the engine).
    const text::GlyphAtlas& a = engine_->atlas();
    gl::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl::TextureSubImage2D(atlas_, 0, 0, 0, a.width(), a.height(), GL_RED, GL_UNSIGNED_BYTE,
                          a.pixels().data());
    gl::PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    uploaded_glyphs_ = a.glyph_count();
  }
  gl::NamedBufferData(vbo_, vertices_.size() * sizeof(Vertex), vertices_.data(), GL_STREAM_DRAW);
  gl::BindFramebuffer(GL_FRAMEBUFFER, fbo);
  gl::Viewport(0, 0, width, height);
  gl::Disable(GL_DEPTH_TEST);
  gl::Enable(GL_BLEND);
  gl::BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  gl::UseProgram(program_.id());
  gl::Uniform2f(program_.uniform("u_viewport"), float(width), float(height));
  gl::Uniform1i(program_.uniform("u_atlas"), 0);
  gl::BindTextureUnit(0, atlas_);
  gl::BindVertexArray(vao_);
  gl::DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices_.size()));
  gl::BindVertexArray(0);
  gl::Disable(GL_BLEND);
  gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
  vertices_.clear();
  gl::check("drawing the overlay");
}

}  // namespace globe::viewer
