// The terrain pass (see terrain_renderer.hpp).
#include "render/terrain_renderer.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <glm/gtc/type_ptr.hpp>

#include "camera/ellipsoid.hpp"
#include "render/terrain_shaders.hpp"

namespace globe::viewer {

namespace {

// Added to a lattice vertex's i to mark it a skirt vertex (set_skirts).
constexpr int kSkirtFlag = 1 << 16;

struct Instance {  // matches the vertex shader's per-instance attributes
  int32_t origin_x, origin_y, apex_x, apex_y;
  int32_t ux, uy, vx, vy;
  int32_t layer, shift;
  int32_t neighbours[4];  // W, E, N, S
};

}  // namespace

TerrainRenderer::TerrainRenderer(int block_size, int lattice, int slots, int width, int height,
                                 bool analysis)
    : size_(block_size), lattice_(lattice), slots_(slots) {
  edge_scales_.fill(0.05f);
  relief_stretches_.fill(1.0f);
  // The head's first line is #version; the skirt flag and lattice follow it.
  std::string head = shaders::kTerrainVertexHead;
  const size_t eol = head.find('\n') + 1;
  head.insert(eol, "#define SKIRT_FLAG " + std::to_string(kSkirtFlag) + "\n#define LATTICE " +
                       std::to_string(lattice) + "\n");
  const std::string vertex = head + shaders::kFrameWorldGlsl + shaders::kTerrainVertexMain;
  draw_program_ = GlProgram("terrain", vertex, with_shading_defines(shaders::kTerrainFragment));
  capture_program_ = GlProgram("terrain capture", vertex, "", {"v_world", "v_key", "v_height"});

  // The lattice: vertices (i, j) with i + j <= L; each cell split along the
  // diagonal from (i+1, j) to (i, j+1), as the tiler's error trees assume.
  const int L = lattice_;
  std::vector<int32_t> verts;
  std::vector<int> index_of((L + 1) * (L + 1), -1);
  for (int j = 0; j <= L; ++j)
    for (int i = 0; i + j <= L; ++i) {
      index_of[j * (L + 1) + i] = static_cast<int>(verts.size() / 2);
      verts.push_back(i);
      verts.push_back(j);
    }
  auto at = [&](int i, int j) { return static_cast<uint32_t>(index_of[j * (L + 1) + i]); };
  std::vector<uint32_t> indices;
  for (int j = 0; j < L; ++j)
    for (int i = 0; i + j < L; ++i) {
      indices.insert(indices.end(), {at(i, j), at(i + 1, j), at(i, j + 1)});
      if (i + j < L - 1)
        indices.insert(indices.end(), {at(i + 1, j + 1), at(i, j + 1), at(i + 1, j)});
    }
  index_count_ = static_cast<GLsizei>(indices.size());
  // Skirts (set_skirts): each perimeter vertex again, flagged (i + kSkirtFlag)
  // for the vertex shader to lower, and a wall of two triangles per
  // perimeter edge, after the lattice's indices (drawn only when enabled).
  std::vector<std::pair<int, int>> rim;  // the perimeter in order: j = 0, the hypotenuse, i = 0
  for (int i = 0; i <= L; ++i)
    rim.push_back({i, 0});
  for (int j = 1; j <= L; ++j)
    rim.push_back({L - j, j});
  for (int j = L - 1; j >= 1; --j)
    rim.push_back({0, j});
  const auto skirt_base = static_cast<uint32_t>(verts.size() / 2);
  for (const auto& [i, j] : rim) {
    verts.push_back(i + kSkirtFlag);
    verts.push_back(j);
  }
  for (size_t k = 0; k < rim.size(); ++k) {
    const size_t n = (k + 1) % rim.size();
    const uint32_t a = at(rim[k].first, rim[k].second), b = at(rim[n].first, rim[n].second);
    const uint32_t a2 = skirt_base + uint32_t(k), b2 = skirt_base + uint32_t(n);
    indices.insert(indices.end(), {a, b, b2, a, b2, a2});
  }
  skirt_index_count_ = static_cast<GLsizei>(indices.size()) - index_count_;

  gl::CreateBuffers(1, &lattice_vbo_);
  gl::NamedBufferStorage(lattice_vbo_, verts.size() * sizeof(int32_t), verts.data(), 0);
  gl::CreateBuffers(1, &index_buffer_);
  gl::NamedBufferStorage(index_buffer_, indices.size() * sizeof(uint32_t), indices.data(), 0);
  gl::CreateBuffers(1, &instance_buffer_);
  gl::CreateVertexArrays(1, &vao_);
  gl::VertexArrayElementBuffer(vao_, index_buffer_);
  gl::VertexArrayVertexBuffer(vao_, 0, lattice_vbo_, 0, 2 * sizeof(int32_t));
  gl::EnableVertexArrayAttrib(vao_, 0);
  gl::VertexArrayAttribIFormat(vao_, 0, 2, GL_INT, 0);
  gl::VertexArrayAttribBinding(vao_, 0, 0);
  const GLuint offsets[4] = {0, 16, 32, 40}, sizes[4] = {4, 4, 2, 4};
  for (GLuint a = 1; a <= 4; ++a) {
    gl::EnableVertexArrayAttrib(vao_, a);
    gl::VertexArrayAttribIFormat(vao_, a, sizes[a - 1], GL_INT, offsets[a - 1]);
    gl::VertexArrayAttribBinding(vao_, a, 1);
  }
  gl::VertexArrayBindingDivisor(vao_, 1, 1);

  GLint max_layers = 0;
  gl::GetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
  if (slots_ > max_layers)
    throw std::runtime_error("the cache needs " + std::to_string(slots_) +
                             " texture layers; this GPU has " + std::to_string(max_layers) +
                             "; lower --cache-mb");
  gl::CreateTextures(GL_TEXTURE_2D_ARRAY, 1, &heights_);
  gl::TextureStorage3D(heights_, 1, GL_R32F, size_, size_, slots_);
  gl::CreateTextures(GL_TEXTURE_2D_ARRAY, 1, &mask_);
  gl::TextureStorage3D(mask_, 1, GL_R8, size_, size_, slots_);
  gl::CreateTextures(GL_TEXTURE_2D, 1, &ramp_);
  gl::TextureStorage2D(ramp_, 1, GL_RGBA8, RampTable::kEntries, 1);
  set_ramp(tabulate(builtin_ramp("hypsometric", 0, 1000), 0, 1000));
  if (analysis) {
    gl::CreateTextures(GL_TEXTURE_2D_ARRAY, 1, &layers_);
    gl::TextureStorage3D(layers_, 1, GL_RGBA16F, size_, size_, slots_);
    gl::CreateTextures(GL_TEXTURE_2D_ARRAY, 1, &flow_);
    gl::TextureStorage3D(flow_, 1, GL_RGB16F, size_, size_, slots_);
  }
  for (GLuint t : {heights_, mask_, ramp_, layers_, flow_}) {
    if (!t) continue;
    gl::TextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl::TextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl::TextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl::TextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  gl::CreateQueries(GL_TIME_ELAPSED, 1, &timer_);
  resize(width, height);
  gl::check("creating the terrain renderer");
}

TerrainRenderer::~TerrainRenderer() {
  gl::DeleteQueries(1, &timer_);
  gl::DeleteFramebuffers(1, &g_.fbo);
  GLuint textures[11] = {heights_,  mask_,        ramp_,    g_.color, g_.position, g_.normal,
                         g_.ground, g_.ground_dy, g_.depth, layers_,  flow_};
  gl::DeleteTextures(layers_ ? 11 : 9, textures);
  GLuint buffers[3] = {lattice_vbo_, index_buffer_, instance_buffer_};
  gl::DeleteBuffers(3, buffers);
  gl::DeleteVertexArrays(1, &vao_);
}

void TerrainRenderer::resize(int width, int height) {
  if (width == g_.width && height == g_.height) return;
  if (g_.fbo) {
    gl::DeleteFramebuffers(1, &g_.fbo);
    GLuint t[6] = {g_.color, g_.position, g_.normal, g_.ground, g_.ground_dy, g_.depth};
    gl::DeleteTextures(6, t);
  }
  g_.width = width;
  g_.height = height;
  auto texture = [&](GLenum format) {
    GLuint t = 0;
    gl::CreateTextures(GL_TEXTURE_2D, 1, &t);
    gl::TextureStorage2D(t, 1, format, width, height);
    gl::TextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl::TextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
  };
  g_.color = texture(GL_RGBA8);
  g_.position = texture(GL_RGBA32F);
  g_.normal = texture(GL_RGBA16F);
  g_.ground = texture(GL_RGBA32F);
  g_.ground_dy = texture(GL_RGBA32F);
  g_.depth = texture(GL_DEPTH_COMPONENT24);
  gl::CreateFramebuffers(1, &g_.fbo);
  gl::NamedFramebufferTexture(g_.fbo, GL_COLOR_ATTACHMENT0, g_.color, 0);
  gl::NamedFramebufferTexture(g_.fbo, GL_COLOR_ATTACHMENT1, g_.position, 0);
  gl::NamedFramebufferTexture(g_.fbo, GL_COLOR_ATTACHMENT2, g_.normal, 0);
  gl::NamedFramebufferTexture(g_.fbo, GL_COLOR_ATTACHMENT3, g_.ground, 0);
  gl::NamedFramebufferTexture(g_.fbo, GL_COLOR_ATTACHMENT4, g_.ground_dy, 0);
  gl::NamedFramebufferTexture(g_.fbo, GL_DEPTH_ATTACHMENT, g_.depth, 0);
  const GLenum buffers[5] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                             GL_COLOR_ATTACHMENT3, GL_COLOR_ATTACHMENT4};
  gl::NamedFramebufferDrawBuffers(g_.fbo, 5, buffers);
  if (gl::CheckNamedFramebufferStatus(g_.fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("the offscreen framebuffer is incomplete");
}

void TerrainRenderer::set_ramp(const RampTable& table) {
  gl::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl::TextureSubImage2D(ramp_, 0, 0, 0, RampTable::kEntries, 1, GL_RGBA, GL_UNSIGNED_BYTE,
                        table.rgba.data());
  ramp_lo_ = table.lo;
  ramp_hi_ = table.hi;
}

void TerrainRenderer::upload(const LoadedBlock& b) {
  gl::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl::TextureSubImage3D(heights_, 0, 0, 0, b.slot, size_, size_, 1, GL_RED, GL_FLOAT,
                        b.heights.data());
  gl::TextureSubImage3D(mask_, 0, 0, 0, b.slot, size_, size_, 1, GL_RED, GL_UNSIGNED_BYTE,
                        b.mask.data());
  if (layers_ && !b.analysis.empty())
    gl::TextureSubImage3D(layers_, 0, 0, 0, b.slot, size_, size_, 1, GL_RGBA, GL_FLOAT,
                          b.analysis.data());
  if (flow_ && !b.flow.empty())
    gl::TextureSubImage3D(flow_, 0, 0, 0, b.slot, size_, size_, 1, GL_RGB, GL_FLOAT, b.flow.data());
}

void TerrainRenderer::upload_instances(const std::vector<Patch>& patches, const View& view,
                                       const WorldFrame& frame) {
  std::vector<Instance> inst(patches.size());
  for (size_t i = 0; i < patches.size(); ++i) {
    const Patch& p = patches[i];
    const int shift = frame.key_zoom() - p.tile.z;
    const int64_t t = frame.tile_size_keys(p.tile.z);
    inst[i] = {static_cast<int32_t>(int64_t{p.tile.x} * t - view.origin.x),
               static_cast<int32_t>(int64_t{p.tile.y} * t - view.origin.y),
               p.apex.x,
               p.apex.y,
               p.u.x,
               p.u.y,
               p.v.x,
               p.v.y,
               p.slot,
               shift,
               {p.neighbours[0], p.neighbours[1], p.neighbours[2], p.neighbours[3]}};
  }
  // A fresh store every frame: the driver orphans the old one if still in use.
  const Instance empty{};
  gl::NamedBufferData(instance_buffer_, std::max<size_t>(inst.size(), 1) * sizeof(Instance),
                      inst.empty() ? &empty : inst.data(), GL_STREAM_DRAW);
  gl::VertexArrayVertexBuffer(vao_, 1, instance_buffer_, 0, sizeof(Instance));
}

void TerrainRenderer::set_frame_uniforms(const GlProgram& p, const View& view,
                                         const WorldFrame& frame, double exaggeration) const {
  gl::UseProgram(p.id());
  gl::UniformMatrix4fv(p.uniform("u_view_proj"), 1, GL_FALSE, glm::value_ptr(view.view_proj));
  gl::Uniform3f(p.uniform("u_scale"),
                static_cast<float>(frame.crs_per_key() * frame.metres_per_crs_x()),
                static_cast<float>(frame.crs_per_key() * frame.metres_per_crs_y()),
                static_cast<float>(frame.height_scale() * exaggeration));
  gl::Uniform2f(p.uniform("u_ground"),
                static_cast<float>(frame.crs_per_key() * frame.ground_per_crs_x()),
                static_cast<float>(frame.crs_per_key() * frame.ground_per_crs_y()));
  int globe = 0;
  if (frame.globe()) {
    const GlobeAnchor& a = frame.anchor(view.origin);
    const bool merc = frame.tiling().scheme == tileformat::Scheme::kWebMercator;
    globe = merc ? 2 : 1;
    // Radians (or mercator y / R) per key unit.
    const double r =
        merc ? frame.crs_per_key() / wgs84::kA : frame.crs_per_key() * std::numbers::pi / 180;
    gl::Uniform2f(p.uniform("u_rad_per_key"), static_cast<float>(r), static_cast<float>(r));
    const int64_t wrap = frame.tiling().scheme == tileformat::Scheme::kWebMercator
                             ? (int64_t{frame.steps()} << frame.key_zoom())
                             : (int64_t{frame.steps()} << frame.key_zoom()) * 2;
    gl::Uniform1i(p.uniform("u_wrap_keys"), static_cast<GLint>(wrap));
    gl::Uniform4f(p.uniform("u_anchor"), static_cast<float>(a.lat),
                  static_cast<float>(std::sin(a.lat)), static_cast<float>(std::cos(a.lat)),
                  static_cast<float>(a.mercator_y));
  }
  gl::Uniform1i(p.uniform("u_globe"), globe);
  gl::Uniform1i(p.uniform("u_heights"), 0);
  gl::BindTextureUnit(0, heights_);
}

RenderTimes TerrainRenderer::draw(const std::vector<Patch>& patches, const View& view,
                                  const WorldFrame& frame, const ShadingSettings& s) {
  upload_instances(patches, view, frame);
  gl::BindFramebuffer(GL_FRAMEBUFFER, g_.fbo);
  gl::Viewport(0, 0, g_.width, g_.height);
  gl::Enable(GL_DEPTH_TEST);
  gl::DepthFunc(GL_LESS);
  gl::DepthMask(GL_TRUE);
  const float sky[4] = {0.62f, 0.72f, 0.82f, 1.0f}, none[4] = {0, 0, 0, 0}, far = 1.0f;
  gl::ClearNamedFramebufferfv(g_.fbo, GL_COLOR, 0, sky);
  gl::ClearNamedFramebufferfv(g_.fbo, GL_COLOR, 1, none);
  gl::ClearNamedFramebufferfv(g_.fbo, GL_COLOR, 2, none);
  gl::ClearNamedFramebufferfv(g_.fbo, GL_COLOR, 3, none);
  gl::ClearNamedFramebufferfv(g_.fbo, GL_COLOR, 4, none);
  gl::ClearNamedFramebufferfv(g_.fbo, GL_DEPTH, 0, &far);
  set_frame_uniforms(draw_program_, view, frame, s.exaggeration);
  const GlProgram& p = draw_program_;
  gl::Uniform1i(p.uniform("u_mask"), 1);
  gl::BindTextureUnit(1, mask_);
  gl::Uniform1f(p.uniform("u_size"), static_cast<float>(size_));
  gl::Uniform1f(p.uniform("u_zscale"), static_cast<float>(frame.height_scale() * s.exaggeration));
  gl::Uniform1f(p.uniform("u_exaggeration"), static_cast<float>(s.exaggeration));
  const double az = s.sun_azimuth_deg * std::numbers::pi / 180,
               alt = s.sun_altitude_deg * std::numbers::pi / 180;
  gl::Uniform3f(p.uniform("u_sun"), static_cast<float>(std::sin(az) * std::cos(alt)),
                static_cast<float>(std::cos(az) * std::cos(alt)),
                static_cast<float>(std::sin(alt)));
  gl::Uniform1i(p.uniform("u_mode"), static_cast<int>(s.mode));
  gl::Uniform2f(p.uniform("u_ramp_range"), static_cast<float>(ramp_lo_),
                static_cast<float>(ramp_hi_));
  gl::Uniform1i(p.uniform("u_ramp"), 2);
  gl::BindTextureUnit(2, ramp_);
  gl::Uniform1i(p.uniform("u_has_gradient"), layers_ && gradient_from_layers_ ? 1 : 0);
  gl::Uniform1fv(p.uniform("u_edge_scale"), 32, edge_scales_.data());
  gl::Uniform1fv(p.uniform("u_relief"), 32, relief_stretches_.data());
  gl::Uniform1f(p.uniform("u_slope_top"), slope_top_deg_);
  gl::Uniform1f(p.uniform("u_sky_low"), sky_low_);
  gl::Uniform1i(p.uniform("u_key_zoom"), frame.key_zoom());
  gl::Uniform1i(p.uniform("u_ao"), s.ambient_occlusion && layers_ ? 1 : 0);
  gl::Uniform1i(p.uniform("u_layers"), 3);
  gl::BindTextureUnit(3, layers_ ? layers_ : mask_);  // any array texture when unused
  gl::Uniform1i(p.uniform("u_flow"), 4);
  gl::BindTextureUnit(4, flow_ ? flow_ : mask_);
  gl::Uniform2f(p.uniform("u_flow_range"), flow_lo_, flow_hi_);
  gl::Uniform1i(p.uniform("u_flow_pulses"), s.flow_phase ? 1 : 0);
  gl::Uniform1f(p.uniform("u_flow_phase"), static_cast<float>(s.flow_phase.value_or(0)));
  gl::Uniform1i(p.uniform("u_layer_ramp"), s.colormap_given ? 1 : 0);
  // The lens centre in GL window coordinates (rows from the bottom).
  gl::Uniform3f(p.uniform("u_lens"), static_cast<float>(s.lens_x),
                static_cast<float>(g_.height - s.lens_y), static_cast<float>(s.lens_radius));
  gl::Uniform1i(p.uniform("u_lens_mode"), static_cast<int>(s.lens_mode));
  gl::Uniform1i(p.uniform("u_lens_shows"), static_cast<int>(s.lens_shows));
  gl::Uniform1f(p.uniform("u_lens_iso"), static_cast<float>(s.lens_isoline_interval));
  gl::Uniform1f(p.uniform("u_iso_interval"), static_cast<float>(s.isoline_interval));
  gl::Uniform1i(p.uniform("u_iso_index"), s.isoline_index);
  gl::Uniform1i(p.uniform("u_iso_of"), static_cast<int>(s.isolines_of));
  gl::Uniform3f(p.uniform("u_iso_rgb"), s.isoline_rgb[0], s.isoline_rgb[1], s.isoline_rgb[2]);
  gl::BindVertexArray(vao_);
  gl::BeginQuery(GL_TIME_ELAPSED, timer_);
  gl::Uniform1f(p.uniform("u_skirt"), skirt_fraction_);
  if (!patches.empty()) {
    gl::DrawElementsInstanced(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr,
                              static_cast<GLsizei>(patches.size()));
    if (skirt_fraction_ > 0)
      gl::DrawElementsInstanced(
          GL_TRIANGLES, skirt_index_count_, GL_UNSIGNED_INT,
          reinterpret_cast<const void*>(static_cast<uintptr_t>(index_count_) * sizeof(uint32_t)),
          static_cast<GLsizei>(patches.size()));
  }
  gl::EndQuery(GL_TIME_ELAPSED);
  GLuint64 ns = 0;
  gl::GetQueryObjectui64v(timer_, GL_QUERY_RESULT, &ns);
  gl::BindVertexArray(0);
  gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl::check("drawing the terrain");
  return {static_cast<double>(ns) / 1e6};
}

std::vector<CapturedVertex> TerrainRenderer::capture_triangles(const std::vector<Patch>& patches,
                                                               const View& view,
                                                               const WorldFrame& frame,
                                                               double exaggeration) {
  static_assert(sizeof(CapturedVertex) == 24, "matches the interleaved feedback varyings");
  std::vector<CapturedVertex> out(patches.size() * triangles_per_patch() * 3);
  const size_t bytes = out.size() * sizeof(CapturedVertex);
  if (patches.empty()) return out;
  upload_instances(patches, view, frame);
  GLuint buffer = 0;
  gl::CreateBuffers(1, &buffer);
  gl::NamedBufferStorage(buffer, bytes, nullptr, 0);
  set_frame_uniforms(capture_program_, view, frame, exaggeration);
  gl::Enable(GL_RASTERIZER_DISCARD);
  gl::BindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, buffer);
  gl::BindVertexArray(vao_);
  gl::BeginTransformFeedback(GL_TRIANGLES);
  gl::DrawElementsInstanced(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr,
                            static_cast<GLsizei>(patches.size()));
  gl::EndTransformFeedback();
  gl::BindVertexArray(0);
  gl::Disable(GL_RASTERIZER_DISCARD);
  gl::GetNamedBufferSubData(buffer, 0, bytes, out.data());
  gl::BindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
  gl::DeleteBuffers(1, &buffer);
  gl::check("capturing the mesh");
  return out;
}

}  // namespace globe::viewer
