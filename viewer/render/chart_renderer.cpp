// The chart pass (see chart_renderer.hpp).
#include "render/chart_renderer.hpp"

#include <algorithm>
#include <cstddef>

#include <glm/gtc/type_ptr.hpp>

#include "render/chart_shaders.hpp"
#include "render/deferred_pass.hpp"
#include "render/gl_buffer.hpp"
#include "render/heatmap_shaders.hpp"
#include "render/key_heights.hpp"
#include "render/readback.hpp"
#include "render/terrain_shaders.hpp"
#include "render/tile_table.hpp"

namespace globe::viewer {

namespace {

constexpr int kTerrainTable = 0;  // shader storage binding

std::string vertex_source(const char* main) {
  return std::string("#version 450 core\n") + shaders::kFrameWorldGlsl + kTileHashGlsl +
         tile_table_glsl("terrain", kTerrainTable) + shaders::kKeyHeightGlsl +
         shaders::kChartCommonVertex + main;
}

// The unit box of a column: 5 faces (no bottom), 2 triangles each, with
// face normals (x, y in -0.5..0.5, z in 0..1).
std::vector<float> box_vertices() {
  struct Face {
    float n[3];
    float c[4][3];  // counter-clockwise seen from outside
  };
  const Face faces[5] = {
      {{0, 0, 1}, {{-.5f, -.5f, 1}, {.5f, -.5f, 1}, {.5f, .5f, 1}, {-.5f, .5f, 1}}},
      {{1, 0, 0}, {{.5f, -.5f, 0}, {.5f, .5f, 0}, {.5f, .5f, 1}, {.5f, -.5f, 1}}},
      {{-1, 0, 0}, {{-.5f, .5f, 0}, {-.5f, -.5f, 0}, {-.5f, -.5f, 1}, {-.5f, .5f, 1}}},
      {{0, 1, 0}, {{.5f, .5f, 0}, {-.5f, .5f, 0}, {-.5f, .5f, 1}, {.5f, .5f, 1}}},
      {{0, -1, 0}, {{-.5f, -.5f, 0}, {.5f, -.5f, 0}, {.5f, -.5f, 1}, {-.5f, -.5f, 1}}},
  };
  std::vector<float> v;
  for (const Face& f : faces)
    for (int i : {0, 1, 2, 0, 2, 3}) {
      v.insert(v.end(), f.c[i], f.c[i] + 3);
      v.insert(v.end(), f.n, f.n + 3);
    }
  return v;
}

// The per-instance attributes (locations 1..7 and 9, binding 1) of `vao`.
void instance_attributes(GLuint vao) {
  gl::EnableVertexArrayAttrib(vao, 1);
  gl::VertexArrayAttribIFormat(vao, 1, 2, GL_INT, offsetof(ChartInstance, key));
  gl::VertexArrayAttribBinding(vao, 1, 1);
  gl::EnableVertexArrayAttrib(vao, 9);
  gl::VertexArrayAttribFormat(vao, 9, 2, GL_FLOAT, GL_FALSE, offsetof(ChartInstance, frac));
  gl::VertexArrayAttribBinding(vao, 9, 1);
  gl::EnableVertexArrayAttrib(vao, 2);
  gl::VertexArrayAttribFormat(vao, 2, 4, GL_FLOAT, GL_FALSE, offsetof(ChartInstance, params));
  gl::VertexArrayAttribBinding(vao, 2, 1);
  for (GLuint a = 3; a <= 6; ++a) {
    gl::EnableVertexArrayAttrib(vao, a);
    gl::VertexArrayAttribFormat(vao, a, 4, GL_FLOAT, GL_FALSE,
                                offsetof(ChartInstance, values) + (a - 3) * 4 * sizeof(float));
    gl::VertexArrayAttribBinding(vao, a, 1);
  }
  gl::EnableVertexArrayAttrib(vao, 7);
  gl::VertexArrayAttribIFormat(vao, 7, 1, GL_UNSIGNED_INT, offsetof(ChartInstance, pick));
  gl::VertexArrayAttribBinding(vao, 7, 1);
}

}  // namespace

ChartRenderer::ChartRenderer(int width, int height) {
  sprite_ = GlProgram("chart sprites", vertex_source(shaders::kChartSpriteMain),
                      shaders::kChartSpriteFragment);
  column_ = GlProgram("chart columns", vertex_source(shaders::kChartColumnMain),
                      shaders::kChartColumnFragment);
  heat_splat_ = GlProgram("heatmap splats", vertex_source(shaders::kHeatSplatMain),
                          shaders::kHeatSplatFragment);
  heat_color_ = GlProgram("heatmap colours", kFullScreenVertex, shaders::kHeatColorFragment);
  gl::CreateVertexArrays(1, &heat_vao_);
  GLuint buffers[4];
  gl::CreateBuffers(4, buffers);
  corner_vbo_ = buffers[0], box_vbo_ = buffers[1], instance_vbo_ = buffers[2],
  terrain_table_ = buffers[3];
  const float corners[12] = {0, 0, 1, 0, 0, 1, 0, 1, 1, 0, 1, 1};
  gl::NamedBufferStorage(corner_vbo_, sizeof corners, corners, 0);
  const std::vector<float> box = box_vertices();
  gl::NamedBufferStorage(box_vbo_, box.size() * sizeof(float), box.data(), 0);
  fill_buffer(instance_vbo_, 0, nullptr);
  fill_buffer(terrain_table_, 0, nullptr);

  gl::CreateVertexArrays(1, &sprite_vao_);
  gl::VertexArrayVertexBuffer(sprite_vao_, 0, corner_vbo_, 0, 2 * sizeof(float));
  gl::EnableVertexArrayAttrib(sprite_vao_, 0);
  gl::VertexArrayAttribFormat(sprite_vao_, 0, 2, GL_FLOAT, GL_FALSE, 0);
  gl::VertexArrayAttribBinding(sprite_vao_, 0, 0);
  instance_attributes(sprite_vao_);
  gl::VertexArrayBindingDivisor(sprite_vao_, 1, 1);

  gl::CreateVertexArrays(1, &column_vao_);
  gl::VertexArrayVertexBuffer(column_vao_, 0, box_vbo_, 0, 6 * sizeof(float));
  gl::EnableVertexArrayAttrib(column_vao_, 0);
  gl::VertexArrayAttribFormat(column_vao_, 0, 3, GL_FLOAT, GL_FALSE, 0);
  gl::VertexArrayAttribBinding(column_vao_, 0, 0);
  gl::EnableVertexArrayAttrib(column_vao_, 8);
  gl::VertexArrayAttribFormat(column_vao_, 8, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float));
  gl::VertexArrayAttribBinding(column_vao_, 8, 0);
  instance_attributes(column_vao_);

  gl::CreateQueries(GL_TIME_ELAPSED, 1, &timer_);
  resize(width, height);
  gl::check("creating the chart renderer");
}

ChartRenderer::~ChartRenderer() {
  GLuint buffers[4] = {corner_vbo_, box_vbo_, instance_vbo_, terrain_table_};
  gl::DeleteBuffers(4, buffers);
  GLuint vaos[3] = {sprite_vao_, column_vao_, heat_vao_};
  gl::DeleteVertexArrays(3, vaos);
  GLuint fbos[2] = {fbo_, density_fbo_};
  gl::DeleteFramebuffers(2, fbos);
  GLuint textures[3] = {color_, picks_, density_};
  gl::DeleteTextures(3, textures);
  if (heat_ramp_) gl::DeleteTextures(1, &heat_ramp_);
  gl::DeleteQueries(1, &timer_);
}

void ChartRenderer::resize(int width, int height) {
  if (width == width_ && height == height_) return;
  width_ = width, height_ = height;
  if (fbo_) {
    GLuint fbos[2] = {fbo_, density_fbo_};
    gl::DeleteFramebuffers(2, fbos);
    GLuint textures[3] = {color_, picks_, density_};
    gl::DeleteTextures(3, textures);
  }
  gl::CreateTextures(GL_TEXTURE_2D, 1, &density_);
  gl::TextureStorage2D(density_, 1, GL_R32F, width, height);
  gl::TextureParameteri(density_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl::TextureParameteri(density_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl::CreateFramebuffers(1, &density_fbo_);
  gl::NamedFramebufferTexture(density_fbo_, GL_COLOR_ATTACHMENT0, density_, 0);
  gl::CreateTextures(GL_TEXTURE_2D, 1, &color_);
  gl::TextureStorage2D(color_, 1, GL_RGBA8, width, height);
  gl::CreateTextures(GL_TEXTURE_2D, 1, &picks_);
  gl::TextureStorage2D(picks_, 1, GL_R32UI, width, height);
  gl::CreateFramebuffers(1, &fbo_);
  gl::NamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, color_, 0);
  gl::NamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT1, picks_, 0);
  const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  gl::NamedFramebufferDrawBuffers(fbo_, 2, buffers);
  bound_depth_ = 0;
}

void ChartRenderer::set_instances(const std::vector<ChartInstance>& instances) {
  fill_buffer(instance_vbo_, instances.size() * sizeof(ChartInstance), instances.data());
  instances_ = static_cast<GLsizei>(instances.size());
  for (GLuint vao : {sprite_vao_, column_vao_})
    gl::VertexArrayVertexBuffer(vao, 1, instance_vbo_, 0, sizeof(ChartInstance));
}

double ChartRenderer::draw(GLuint input_fbo, const GBuffer& g, const View& view,
                           const WorldFrame& world, const TerrainRenderer& terrain,
                           const TerrainHeights& heights, const ChartDrawStyle& style,
                           double exaggeration, glm::vec3 sun) {
  if (bound_depth_ != g.depth) {
    gl::NamedFramebufferTexture(fbo_, GL_DEPTH_ATTACHMENT, g.depth, 0);
    bound_depth_ = g.depth;
  }
  copy_input(input_fbo);
  const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  gl::NamedFramebufferDrawBuffers(fbo_, 2, both);
  const GLuint none = 0;
  gl::ClearNamedFramebufferuiv(fbo_, GL_COLOR, 1, &none);
  if (instances_ == 0) return 0;

  const bool columns = style.kind == ChartKind::kColumn;
  const GlProgram& p = columns ? column_ : sprite_;
  prepare(p, view, world, terrain, heights, exaggeration);
  gl::Uniform1i(p.uniform("u_fields"), style.fields);
  gl::Uniform4fv(p.uniform("u_colors"), kMaxChartFields, glm::value_ptr(style.colors[0]));

  gl::BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  gl::Viewport(0, 0, width_, height_);
  gl::Enable(GL_DEPTH_TEST);
  if (style.depth == ChartDepth::kOnTop) {
    const float far = 1.0f;
    gl::ClearNamedFramebufferfv(fbo_, GL_DEPTH, 0, &far);
  }
  gl::BeginQuery(GL_TIME_ELAPSED, timer_);
  if (columns) {
    gl::DepthFunc(GL_LESS);
    gl::DepthMask(GL_TRUE);
    gl::Uniform3f(p.uniform("u_sun"), sun.x, sun.y, sun.z);
    gl::Uniform1f(p.uniform("u_column_gap"), 0.15f);
    gl::VertexArrayBindingDivisor(column_vao_, 1, static_cast<GLuint>(style.fields));
    gl::BindVertexArray(column_vao_);
    gl::DrawArraysInstanced(GL_TRIANGLES, 0, 30, instances_ * style.fields);
  } else {
    // Back to front, blended, tested against the terrain but not each other.
    gl::DepthFunc(GL_LEQUAL);
    gl::DepthMask(GL_FALSE);
    gl::Enable(GL_BLEND);
    gl::BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    gl::Uniform2f(p.uniform("u_viewport"), static_cast<float>(width_), static_cast<float>(height_));
    gl::Uniform1f(p.uniform("u_focal_px"), static_cast<float>(view.pixels_per_radian));
    gl::Uniform1i(p.uniform("u_kind"), style.kind == ChartKind::kPie   ? 0
                                       : style.kind == ChartKind::kBar ? 1
                                                                       : 2);
    gl::Uniform4f(p.uniform("u_outline"), style.outline.r, style.outline.g, style.outline.b,
                  style.outline.a);
    gl::Uniform1f(p.uniform("u_opacity"), style.opacity);
    gl::BindVertexArray(sprite_vao_);
    gl::DrawArraysInstanced(GL_TRIANGLES, 0, 6, instances_);
    gl::Disable(GL_BLEND);
    gl::DepthMask(GL_TRUE);
  }
  gl::EndQuery(GL_TIME_ELAPSED);
  GLuint64 ns = 0;
  gl::GetQueryObjectui64v(timer_, GL_QUERY_RESULT, &ns);
  gl::BindVertexArray(0);
  gl::Disable(GL_DEPTH_TEST);
  gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl::check("drawing the charts");
  return static_cast<double>(ns) / 1e6;
}

void ChartRenderer::copy_input(GLuint input_fbo) {
  gl::NamedFramebufferReadBuffer(input_fbo, GL_COLOR_ATTACHMENT0);
  gl::NamedFramebufferDrawBuffers(fbo_, 1, std::array<GLenum, 1>{GL_COLOR_ATTACHMENT0}.data());
  gl::BlitNamedFramebuffer(input_fbo, fbo_, 0, 0, width_, height_, 0, 0, width_, height_,
                           GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

void ChartRenderer::prepare(const GlProgram& p, const View& view, const WorldFrame& world,
                            const TerrainRenderer& terrain, const TerrainHeights& heights,
                            double exaggeration) {
  bind_key_heights(p, terrain_table_, kTerrainTable, view, world, terrain, heights, exaggeration);
}

double ChartRenderer::draw_heatmap(GLuint input_fbo, const GBuffer& g, const View& view,
                                   const WorldFrame& world, const TerrainRenderer& terrain,
                                   const TerrainHeights& heights, const HeatmapStyle& style,
                                   double exaggeration) {
  gl::BeginQuery(GL_TIME_ELAPSED, timer_);
  // 1. The density: every place's kernel, added up per pixel.
  const float zero[4] = {0, 0, 0, 0};
  gl::ClearNamedFramebufferfv(density_fbo_, GL_COLOR, 0, zero);
  if (instances_ > 0) {
    const GlProgram& s = heat_splat_;
    prepare(s, view, world, terrain, heights, exaggeration);
    gl::Uniform2f(s.uniform("u_viewport"), static_cast<float>(width_), static_cast<float>(height_));
    gl::Uniform1f(s.uniform("u_focal_px"), static_cast<float>(view.pixels_per_radian));
    gl::Uniform1f(s.uniform("u_margin"), style.margin_world);
    gl::BindTextureUnit(2, g.ground);  // unit 0: the terrain's heights
    gl::BindTextureUnit(3, g.position);
    gl::Uniform1i(s.uniform("u_gbuffer_ground"), 2);
    gl::Uniform1i(s.uniform("u_gbuffer_position"), 3);
    gl::BindFramebuffer(GL_FRAMEBUFFER, density_fbo_);
    gl::Viewport(0, 0, width_, height_);
    gl::Disable(GL_DEPTH_TEST);
    gl::Enable(GL_BLEND);
    gl::BlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
    gl::BindVertexArray(sprite_vao_);
    gl::DrawArraysInstanced(GL_TRIANGLES, 0, 6, instances_);
    gl::Disable(GL_BLEND);
    gl::check("splatting the heatmap");
  }
  // The ramp's top: the frame's largest density.
  const std::vector<float> d = read_r32f(density_fbo_, 0, 0, 0, width_, height_);
  density_top_ = d.empty() ? 0 : *std::max_element(d.begin(), d.end());
  // 2. The colours, blended over the input image.
  copy_input(input_fbo);
  const GlProgram& c = heat_color_;
  gl::UseProgram(c.id());
  gl::BindTextureUnit(1, density_);
  gl::Uniform1i(c.uniform("u_density"), 1);
  gl::Uniform1f(c.uniform("u_top"), density_top_);
  gl::Uniform1f(c.uniform("u_opacity"), style.opacity);
  gl::Uniform1i(c.uniform("u_has_ramp"), style.ramp.empty() ? 0 : 1);
  if (!style.ramp.empty()) {  // the colour file's ramp
    if (!heat_ramp_) {
      gl::CreateTextures(GL_TEXTURE_2D, 1, &heat_ramp_);
      gl::TextureStorage2D(heat_ramp_, 1, GL_RGBA8, 256, 1);
      gl::TextureParameteri(heat_ramp_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      gl::TextureParameteri(heat_ramp_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      gl::TextureParameteri(heat_ramp_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    }
    gl::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl::TextureSubImage2D(heat_ramp_, 0, 0, 0, 256, 1, GL_RGBA, GL_UNSIGNED_BYTE,
                          style.ramp.data());
    gl::BindTextureUnit(2, heat_ramp_);
    gl::Uniform1i(c.uniform("u_heat_ramp"), 2);
  }
  gl::BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  gl::Viewport(0, 0, width_, height_);
  gl::Disable(GL_DEPTH_TEST);
  gl::Enable(GL_BLEND);
  gl::BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  gl::BindVertexArray(heat_vao_);
  gl::DrawArrays(GL_TRIANGLES, 0, 3);
  gl::Disable(GL_BLEND);
  const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  gl::NamedFramebufferDrawBuffers(fbo_, 2, both);
  const GLuint none = 0;
  gl::ClearNamedFramebufferuiv(fbo_, GL_COLOR, 1, &none);  // no chart to pick
  gl::EndQuery(GL_TIME_ELAPSED);
  GLuint64 ns = 0;
  gl::GetQueryObjectui64v(timer_, GL_QUERY_RESULT, &ns);
  gl::BindVertexArray(0);
  gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl::check("drawing the heatmap");
  return static_cast<double>(ns) / 1e6;
}

float ChartRenderer::density_at(int x, int y) const {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return 0;
  return read_r32f(density_fbo_, 0, x, height_ - 1 - y, 1, 1).at(0);
}

uint32_t ChartRenderer::pick(int x, int y) const {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return 0;
  return read_u32(fbo_, 1, x, y, height_);
}

}  // namespace globe::viewer
