// The label passes (see label_renderer.hpp).
#include "render/label_renderer.hpp"

#include <algorithm>
#include <array>
#include <cstddef>

#include "render/gl_buffer.hpp"
#include "render/key_heights.hpp"
#include "render/label_shaders.hpp"
#include "render/terrain_shaders.hpp"
#include "render/tile_table.hpp"

namespace globe::viewer {

namespace {

constexpr int kTerrainTable = 0;  // shader storage binding
constexpr int kRow = 1024;        // texels per row of the results image

}  // namespace

LabelRenderer::LabelRenderer(int width, int height) {
  probe_ = GlProgram("label probes",
                     std::string("#version 450 core\n") + shaders::kFrameWorldGlsl + kTileHashGlsl +
                         tile_table_glsl("terrain", kTerrainTable) + shaders::kKeyHeightGlsl +
                         shaders::kLabelProbeVertex,
                     shaders::kLabelPointFragment);
  depth_ =
      GlProgram("label depth samples", shaders::kLabelDepthVertex, shaders::kLabelPointFragment);
  glyph_ = GlProgram("label glyphs", shaders::kGlyphVertex, shaders::kGlyphFragment);
  GLuint buffers[6];
  gl::CreateBuffers(6, buffers);
  probe_vbo_ = buffers[0], depth_vbo_ = buffers[1], corner_vbo_ = buffers[2],
  glyph_vbo_ = buffers[3], terrain_table_ = buffers[4], extra_vbo_ = buffers[5];
  for (GLuint b : {probe_vbo_, depth_vbo_, glyph_vbo_, terrain_table_, extra_vbo_})
    fill_buffer(b, 0, nullptr);
  const float corners[12] = {0, 0, 1, 0, 0, 1, 0, 1, 1, 0, 1, 1};
  gl::NamedBufferStorage(corner_vbo_, sizeof corners, corners, 0);

  for (GLuint* vao : {&probe_vao_, &extra_vao_}) {
    gl::CreateVertexArrays(1, vao);
    gl::EnableVertexArrayAttrib(*vao, 0);
    gl::VertexArrayAttribIFormat(*vao, 0, 2, GL_INT, offsetof(LabelProbe, key));
    gl::VertexArrayAttribBinding(*vao, 0, 0);
    gl::EnableVertexArrayAttrib(*vao, 1);
    gl::VertexArrayAttribFormat(*vao, 1, 2, GL_FLOAT, GL_FALSE, offsetof(LabelProbe, frac));
    gl::VertexArrayAttribBinding(*vao, 1, 0);
  }

  gl::CreateVertexArrays(1, &depth_vao_);
  gl::EnableVertexArrayAttrib(depth_vao_, 0);
  gl::VertexArrayAttribFormat(depth_vao_, 0, 2, GL_FLOAT, GL_FALSE, 0);
  gl::VertexArrayAttribBinding(depth_vao_, 0, 0);

  gl::CreateVertexArrays(1, &glyph_vao_);
  gl::VertexArrayVertexBuffer(glyph_vao_, 0, corner_vbo_, 0, 2 * sizeof(float));
  gl::EnableVertexArrayAttrib(glyph_vao_, 0);
  gl::VertexArrayAttribFormat(glyph_vao_, 0, 2, GL_FLOAT, GL_FALSE, 0);
  gl::VertexArrayAttribBinding(glyph_vao_, 0, 0);
  for (GLuint a = 1; a <= 4; ++a) {
    gl::EnableVertexArrayAttrib(glyph_vao_, a);
    gl::VertexArrayAttribFormat(glyph_vao_, a, 4, GL_FLOAT, GL_FALSE, (a - 1) * 4 * sizeof(float));
    gl::VertexArrayAttribBinding(glyph_vao_, a, 1);
  }
  gl::VertexArrayBindingDivisor(glyph_vao_, 1, 1);
  gl::CreateQueries(GL_TIME_ELAPSED, 1, &timer_);
  resize(width, height);
  gl::check("creating the label renderer");
}

LabelRenderer::~LabelRenderer() {
  GLuint buffers[6] = {probe_vbo_, depth_vbo_, corner_vbo_, glyph_vbo_, terrain_table_, extra_vbo_};
  gl::DeleteBuffers(6, buffers);
  GLuint vaos[4] = {probe_vao_, depth_vao_, glyph_vao_, extra_vao_};
  gl::DeleteVertexArrays(4, vaos);
  GLuint fbos[2] = {fbo_, result_fbo_};
  gl::DeleteFramebuffers(2, fbos);
  GLuint textures[3] = {color_, result_, atlas_};
  gl::DeleteTextures(3, textures);
  gl::DeleteQueries(1, &timer_);
}

void LabelRenderer::resize(int width, int height) {
  if (width == width_ && height == height_) return;
  width_ = width, height_ = height;
  if (fbo_) {
    gl::DeleteFramebuffers(1, &fbo_);
    gl::DeleteTextures(1, &color_);
  }
  gl::CreateTextures(GL_TEXTURE_2D, 1, &color_);
  gl::TextureStorage2D(color_, 1, GL_RGBA8, width, height);
  gl::CreateFramebuffers(1, &fbo_);
  gl::NamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, color_, 0);
}

void LabelRenderer::set_probes(const std::vector<LabelProbe>& probes) {
  fill_buffer(probe_vbo_, probes.size() * sizeof(LabelProbe), probes.data());
  gl::VertexArrayVertexBuffer(probe_vao_, 0, probe_vbo_, 0, sizeof(LabelProbe));
  probes_ = probes.size();
}

std::vector<float> LabelRenderer::run_points(const GlProgram& p, GLuint vao, size_t count,
                                             int channels) {
  const int rows = static_cast<int>((count + kRow - 1) / kRow);
  if (rows > result_h_) {
    if (result_fbo_) {
      gl::DeleteFramebuffers(1, &result_fbo_);
      gl::DeleteTextures(1, &result_);
    }
    result_w_ = kRow, result_h_ = std::max(rows, 2 * result_h_);
    gl::CreateTextures(GL_TEXTURE_2D, 1, &result_);
    gl::TextureStorage2D(result_, 1, GL_RGBA32F, result_w_, result_h_);
    gl::CreateFramebuffers(1, &result_fbo_);
    gl::NamedFramebufferTexture(result_fbo_, GL_COLOR_ATTACHMENT0, result_, 0);
  }
  gl::Uniform1i(p.uniform("u_row"), kRow);
  gl::Uniform1i(p.uniform("u_rows"), result_h_);
  gl::BindFramebuffer(GL_FRAMEBUFFER, result_fbo_);
  gl::Viewport(0, 0, result_w_, result_h_);
  gl::Disable(GL_DEPTH_TEST);
  gl::Disable(GL_BLEND);
  gl::BindVertexArray(vao);
  gl::DrawArrays(GL_POINTS, 0, static_cast<GLsizei>(count));
  gl::BindVertexArray(0);
  std::vector<float> rgba(size_t(kRow) * size_t(rows) * 4);
  gl::PixelStorei(GL_PACK_ALIGNMENT, 4);
  gl::ReadPixels(0, 0, kRow, rows, GL_RGBA, GL_FLOAT, rgba.data());
  gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl::check("the label points");
  std::vector<float> out(count * size_t(channels));
  for (size_t i = 0; i < count; ++i)
    for (int c = 0; c < channels; ++c)
      out[i * size_t(channels) + size_t(c)] = rgba[i * 4 + size_t(c)];
  return out;
}

std::vector<ProbeResult> LabelRenderer::project(const View& view, const WorldFrame& world,
                                                const TerrainRenderer& terrain,
                                                const TerrainHeights& heights,
                                                double exaggeration) {
  return run_probes(probe_vao_, probes_, view, world, terrain, heights, exaggeration);
}

std::vector<ProbeResult> LabelRenderer::project(const std::vector<LabelProbe>& points,
                                                const View& view, const WorldFrame& world,
                                                const TerrainRenderer& terrain,
                                                const TerrainHeights& heights,
                                                double exaggeration) {
  if (points.empty()) return {};
  fill_buffer(extra_vbo_, points.size() * sizeof(LabelProbe), points.data());
  gl::VertexArrayVertexBuffer(extra_vao_, 0, extra_vbo_, 0, sizeof(LabelProbe));
  return run_probes(extra_vao_, points.size(), view, world, terrain, heights, exaggeration);
}

std::vector<ProbeResult> LabelRenderer::run_probes(GLuint vao, size_t count, const View& view,
                                                   const WorldFrame& world,
                                                   const TerrainRenderer& terrain,
                                                   const TerrainHeights& heights,
                                                   double exaggeration) {
  std::vector<ProbeResult> out(count);
  if (count == 0) return out;
  const GlProgram& p = probe_;
  bind_key_heights(p, terrain_table_, kTerrainTable, view, world, terrain, heights, exaggeration);
  gl::Uniform2f(p.uniform("u_viewport"), static_cast<float>(width_), static_cast<float>(height_));
  const std::vector<float> r = run_points(p, vao, count, 4);
  for (size_t i = 0; i < count; ++i)
    out[i] = {r[i * 4], r[i * 4 + 1], r[i * 4 + 2], r[i * 4 + 3] > 0.5f};
  return out;
}

std::vector<float> LabelRenderer::terrain_distances(const std::vector<float>& pixels_xy,
                                                    const GBuffer& g, const View& view) {
  const size_t n = pixels_xy.size() / 2;
  if (n == 0) return {};
  fill_buffer(depth_vbo_, pixels_xy.size() * sizeof(float), pixels_xy.data());
  gl::VertexArrayVertexBuffer(depth_vao_, 0, depth_vbo_, 0, 2 * sizeof(float));
  const GlProgram& p = depth_;
  gl::UseProgram(p.id());
  gl::BindTextureUnit(3, g.position);
  gl::Uniform1i(p.uniform("u_position"), 3);
  gl::Uniform3f(p.uniform("u_eye"), static_cast<float>(view.eye.x), static_cast<float>(view.eye.y),
                static_cast<float>(view.eye.z));
  gl::Uniform2i(p.uniform("u_size"), g.width, g.height);
  return run_points(p, depth_vao_, n, 1);
}

void LabelRenderer::upload_atlas(const uint8_t* pixels, int width, int height, int y0, int y1) {
  if (width != atlas_w_ || height != atlas_h_) {
    if (atlas_) gl::DeleteTextures(1, &atlas_);
    gl::CreateTextures(GL_TEXTURE_2D, 1, &atlas_);
    gl::TextureStorage2D(atlas_, 1, GL_R8, width, height);
    gl::TextureParameteri(atlas_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl::TextureParameteri(atlas_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl::TextureParameteri(atlas_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl::TextureParameteri(atlas_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    atlas_w_ = width, atlas_h_ = height;
    y0 = 0, y1 = height;
  }
  if (y1 <= y0) return;
  gl::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl::TextureSubImage2D(atlas_, 0, 0, y0, width, y1 - y0, GL_RED, GL_UNSIGNED_BYTE,
                        pixels + size_t(y0) * size_t(width));
  gl::PixelStorei(GL_UNPACK_ALIGNMENT, 4);
  gl::check("uploading the glyph atlas");
}

double LabelRenderer::draw(GLuint input_fbo, const std::vector<GlyphQuad>& glyphs,
                           const LabelColors& colors) {
  gl::NamedFramebufferReadBuffer(input_fbo, GL_COLOR_ATTACHMENT0);
  gl::BlitNamedFramebuffer(input_fbo, fbo_, 0, 0, width_, height_, 0, 0, width_, height_,
                           GL_COLOR_BUFFER_BIT, GL_NEAREST);
  if (glyphs.empty() || !atlas_) return 0;
  fill_buffer(glyph_vbo_, glyphs.size() * sizeof(GlyphQuad), glyphs.data());
  gl::VertexArrayVertexBuffer(glyph_vao_, 1, glyph_vbo_, 0, sizeof(GlyphQuad));
  const GlProgram& p = glyph_;
  gl::UseProgram(p.id());
  gl::BindTextureUnit(1, atlas_);
  gl::Uniform1i(p.uniform("u_atlas"), 1);
  gl::Uniform2f(p.uniform("u_viewport"), static_cast<float>(width_), static_cast<float>(height_));
  gl::Uniform2f(p.uniform("u_atlas_size"), static_cast<float>(atlas_w_),
                static_cast<float>(atlas_h_));
  gl::Uniform3f(p.uniform("u_fill"), colors.fill.r, colors.fill.g, colors.fill.b);
  gl::Uniform3f(p.uniform("u_halo"), colors.halo.r, colors.halo.g, colors.halo.b);
  gl::BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  gl::Viewport(0, 0, width_, height_);
  gl::Disable(GL_DEPTH_TEST);
  gl::Enable(GL_BLEND);
  gl::BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  gl::BeginQuery(GL_TIME_ELAPSED, timer_);
  gl::BindVertexArray(glyph_vao_);
  gl::DrawArraysInstanced(GL_TRIANGLES, 0, 6, static_cast<GLsizei>(glyphs.size()));
  gl::EndQuery(GL_TIME_ELAPSED);
  GLuint64 ns = 0;
  gl::GetQueryObjectui64v(timer_, GL_QUERY_RESULT, &ns);
  gl::BindVertexArray(0);
  gl::Disable(GL_BLEND);
  gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl::check("drawing the labels");
  return static_cast<double>(ns) / 1e6;
}

}  // namespace globe::viewer
