// The imagery pass (see image_renderer.hpp).
#include "render/image_renderer.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "render/crs_cross_glsl.hpp"
#include "render/deferred_pass.hpp"
#include "render/gl_buffer.hpp"
#include "render/image_shaders.hpp"
#include "render/tile_table.hpp"

namespace globe::viewer {

namespace {

enum Binding : GLuint { kTables = 0, kRequests = 1, kUsed = 2 };
enum Unit : GLuint {
  kColor = 0,
  kPosition = 1,
  kGround = 2,
  kGroundDy = 3,
  kGrids = 4,
  kFirstImage = 5
};

std::string at(const char* name, size_t i) {
  return std::string(name) + "[" + std::to_string(i) + "]";
}

}  // namespace

ImageRenderer::ImageRenderer(int width, int height, int grid_n) : grid_n_(grid_n) {
  program_ =
      GlProgram("imagery pass", kFullScreenVertex,
                std::string("#version 450 core\n") + kTileHashGlsl + deferred_pass_glsl(kRequests) +
                    shaders::kCrsCrossGlsl + shaders::kImageFragment);
  GLuint buffers[3];
  gl::CreateBuffers(3, buffers);
  tables_ = buffers[0], requests_ = buffers[1], used_ = buffers[2];
  gl::NamedBufferStorage(requests_, kRequestSlots * 2 * sizeof(uint32_t), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
  fill_buffer(tables_, 0, nullptr);
  fill_buffer(used_, 0, nullptr);
  gl::CreateVertexArrays(1, &vao_);
  gl::CreateQueries(GL_TIME_ELAPSED, 1, &timer_);
  resize(width, height);
  gl::check("creating the imagery renderer");
}

ImageRenderer::~ImageRenderer() {
  GLuint buffers[3] = {tables_, requests_, used_};
  gl::DeleteBuffers(3, buffers);
  gl::DeleteVertexArrays(1, &vao_);
  gl::DeleteFramebuffers(1, &fbo_);
  gl::DeleteTextures(1, &output_);
  if (grids_texture_) gl::DeleteTextures(1, &grids_texture_);
  for (const Layer& l : layers_)
    gl::DeleteTextures(1, &l.texture);
  gl::DeleteQueries(1, &timer_);
}

void ImageRenderer::resize(int width, int height) {
  if (width == width_ && height == height_) return;
  width_ = width, height_ = height;
  if (fbo_) {
    gl::DeleteFramebuffers(1, &fbo_);
    gl::DeleteTextures(1, &output_);
  }
  gl::CreateTextures(GL_TEXTURE_2D, 1, &output_);
  gl::TextureStorage2D(output_, 1, GL_RGBA8, width, height);
  gl::TextureParameteri(output_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl::TextureParameteri(output_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl::CreateFramebuffers(1, &fbo_);
  gl::NamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, output_, 0);
}

void ImageRenderer::add_layer(const ImageCache& cache, const std::vector<float>& grid) {
  if (layers_.size() >= size_t(shaders::kMaxImageLayers))
    throw std::invalid_argument("more than " + std::to_string(shaders::kMaxImageLayers) +
                                " image layers");
  Layer l;
  l.slots = cache.slots();
  l.tile_px = cache.package().tile_size;
  l.min_zoom = cache.package().min_zoom;
  l.max_zoom = cache.package().max_zoom;
  gl::CreateTextures(GL_TEXTURE_2D_ARRAY, 1, &l.texture);
  gl::TextureStorage3D(l.texture, cache.levels(), GL_RGBA8, l.tile_px, l.tile_px, l.slots);
  gl::TextureParameteri(l.texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  gl::TextureParameteri(l.texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl::TextureParameteri(l.texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl::TextureParameteri(l.texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  layers_.push_back(l);
  grids_.push_back(grid.empty() ? std::vector<float>(size_t(grid_n_) * grid_n_ * 2, 0.0f) : grid);
  grids_dirty_ = true;
  gl::check("creating an image layer's texture array");
}

void ImageRenderer::upload(size_t layer, uint32_t slot, const ImageMips& mips) {
  const Layer& l = layers_.at(layer);
  int size = l.tile_px;
  gl::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  for (size_t level = 0; level < mips.levels.size(); ++level, size = std::max(size / 2, 1))
    gl::TextureSubImage3D(l.texture, static_cast<GLint>(level), 0, 0, static_cast<GLint>(slot),
                          size, size, 1, GL_RGBA, GL_UNSIGNED_BYTE, mips.levels[level].data());
}

double ImageRenderer::draw(const GBuffer& g, const View& view, const WorldFrame& world,
                           const std::vector<const ImageCache*>& caches,
                           const std::vector<ImageLayerFrame>& frames, ImageLighting lighting,
                           float light_norm, uint32_t frame, ImageFeedback& fb) {
  if (grids_dirty_) {
    if (grids_texture_) gl::DeleteTextures(1, &grids_texture_);
    gl::CreateTextures(GL_TEXTURE_2D_ARRAY, 1, &grids_texture_);
    const GLsizei n = static_cast<GLsizei>(std::max<size_t>(grids_.size(), 1));
    gl::TextureStorage3D(grids_texture_, 1, GL_RG32F, grid_n_, grid_n_, n);
    gl::TextureParameteri(grids_texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl::TextureParameteri(grids_texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    for (size_t i = 0; i < grids_.size(); ++i)
      gl::TextureSubImage3D(grids_texture_, 0, 0, 0, static_cast<GLint>(i), grid_n_, grid_n_, 1,
                            GL_RG, GL_FLOAT, grids_[i].data());
    grids_dirty_ = false;
  }
  // Tables of every layer, one after the other; used flags per slot likewise.
  std::vector<glm::uvec4> tables;
  std::vector<uint32_t> table_offset, table_mask, slot_offset;
  uint32_t slots = 0;
  for (const ImageCache* c : caches) {
    const auto t = build_tile_table(c->table());
    table_offset.push_back(static_cast<uint32_t>(tables.size()));
    table_mask.push_back(static_cast<uint32_t>(t.size() - 1));
    tables.insert(tables.end(), t.begin(), t.end());
    slot_offset.push_back(slots);
    slots += static_cast<uint32_t>(c->slots());
  }
  fill_buffer(tables_, tables.size() * sizeof(glm::uvec4), tables.data());
  const std::vector<uint32_t> zeros(std::max<size_t>(slots, kRequestSlots * 2), 0);
  fill_buffer(used_, slots * sizeof(uint32_t), zeros.data());
  gl::NamedBufferSubData(requests_, 0, kRequestSlots * 2 * sizeof(uint32_t), zeros.data());

  gl::BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  gl::Viewport(0, 0, width_, height_);
  gl::Disable(GL_DEPTH_TEST);
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, kTables, tables_);
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, kRequests, requests_);
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, kUsed, used_);
  const GlProgram& p = program_;
  gl::UseProgram(p.id());
  gl::BindTextureUnit(kColor, g.color);
  gl::BindTextureUnit(kPosition, g.position);
  gl::BindTextureUnit(kGround, g.ground);
  gl::BindTextureUnit(kGroundDy, g.ground_dy);
  gl::BindTextureUnit(kGrids, grids_texture_);
  gl::Uniform1i(p.uniform("u_color"), kColor);
  gl::Uniform1i(p.uniform("u_position"), kPosition);
  gl::Uniform1i(p.uniform("u_ground"), kGround);
  gl::Uniform1i(p.uniform("u_ground_dy"), kGroundDy);
  gl::Uniform1i(p.uniform("u_grids"), kGrids);
  gl::Uniform1i(p.uniform("u_grid_n"), grid_n_);
  const glm::mat4 inv = glm::mat4(glm::inverse(view.proj * view.view));
  gl::UniformMatrix4fv(p.uniform("u_inv_view_proj"), 1, GL_FALSE, glm::value_ptr(inv));
  gl::Uniform3f(p.uniform("u_eye"), float(view.eye.x), float(view.eye.y), float(view.eye.z));
  gl::Uniform2f(p.uniform("u_crs_per_m"), float(1 / world.ground_per_crs_x()),
                float(1 / world.ground_per_crs_y()));
  gl::Uniform1i(p.uniform("u_lit"), lighting == ImageLighting::kHillshade ? 1 : 0);
  gl::Uniform1f(p.uniform("u_light_norm"), light_norm);
  gl::Uniform1ui(p.uniform("u_request_mask"), kRequestSlots - 1);
  gl::Uniform1ui(p.uniform("u_frame"), frame);
  const size_t n = std::min(frames.size(), layers_.size());
  gl::Uniform1i(p.uniform("u_layers"), static_cast<int>(n));
  gl::Uniform3f(p.uniform("u_lens_only"), lens_only_.x, float(height_) - lens_only_.y,
                lens_only_.z);
  for (size_t i = 0; i < n; ++i) {
    const ImageLayerFrame& f = frames[i];
    const Layer& l = layers_[i];
    gl::BindTextureUnit(kFirstImage + static_cast<GLuint>(i), l.texture);
    gl::Uniform1i(p.uniform(at("u_images", i).c_str()), kFirstImage + static_cast<int>(i));
    gl::Uniform1i(p.uniform(at("u_mode", i).c_str()), f.mode);
    gl::Uniform2i(p.uniform(at("u_base", i).c_str()), f.base.x, f.base.y);
    gl::Uniform2f(p.uniform(at("u_frac", i).c_str()), f.frac.x, f.frac.y);
    gl::Uniform2f(p.uniform(at("u_per_unit", i).c_str()), f.per_unit.x, f.per_unit.y);
    gl::Uniform1i(p.uniform(at("u_ref_zoom", i).c_str()), f.ref_zoom);
    gl::Uniform1i(p.uniform(at("u_wrap", i).c_str()), caches[i]->package().tiling.wrap_tiles());
    gl::Uniform1i(p.uniform(at("u_min_zoom", i).c_str()), l.min_zoom);
    gl::Uniform1i(p.uniform(at("u_max_zoom", i).c_str()), l.max_zoom);
    gl::Uniform1f(p.uniform(at("u_tile_px", i).c_str()), float(l.tile_px));
    gl::Uniform1f(p.uniform(at("u_opacity", i).c_str()), f.opacity);
    gl::Uniform2f(p.uniform(at("u_param", i).c_str()), f.param.x, f.param.y);
    gl::Uniform2f(p.uniform(at("u_grid_org", i).c_str()), f.grid_org.x, f.grid_org.y);
    gl::Uniform2f(p.uniform(at("u_grid_inv_cell", i).c_str()), f.grid_inv_cell.x,
                  f.grid_inv_cell.y);
    gl::Uniform1ui(p.uniform(at("u_table_offset", i).c_str()), table_offset[i]);
    gl::Uniform1ui(p.uniform(at("u_table_mask", i).c_str()), table_mask[i]);
    gl::Uniform1ui(p.uniform(at("u_slot_offset", i).c_str()), slot_offset[i]);
  }
  // Unused sampler units still need a texture of the declared type.
  for (size_t i = n; i < size_t(shaders::kMaxImageLayers); ++i) {
    gl::BindTextureUnit(kFirstImage + static_cast<GLuint>(i), grids_texture_);
    gl::Uniform1i(p.uniform(at("u_images", i).c_str()), kFirstImage + static_cast<int>(i));
  }
  gl::BindVertexArray(vao_);
  gl::BeginQuery(GL_TIME_ELAPSED, timer_);
  gl::DrawArrays(GL_TRIANGLES, 0, 3);
  gl::EndQuery(GL_TIME_ELAPSED);

  // Feedback.
  gl::MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<uint32_t> req(kRequestSlots * 2), used(slots);
  gl::GetNamedBufferSubData(requests_, 0, req.size() * 4, req.data());
  if (slots) gl::GetNamedBufferSubData(used_, 0, used.size() * 4, used.data());
  fb.requests.assign(n, {});
  fb.used.assign(n, {});
  for (const TileRequest& r : decode_tile_requests(req))
    if (r.tag < n) fb.requests[r.tag].push_back(r.id);
  for (size_t i = 0; i < n; ++i)
    for (uint32_t s = 0; s < uint32_t(caches[i]->slots()); ++s)
      if (used[slot_offset[i] + s] == frame) fb.used[i].push_back(s);
  GLuint64 ns = 0;
  gl::GetQueryObjectui64v(timer_, GL_QUERY_RESULT, &ns);
  gl::BindVertexArray(0);
  gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl::check("drawing the imagery");
  return static_cast<double>(ns) / 1e6;
}

}  // namespace globe::viewer
