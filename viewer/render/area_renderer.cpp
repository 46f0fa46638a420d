// The area fill pass (see area_renderer.hpp).
#include "render/area_renderer.hpp"

#include <algorithm>
#include <bit>

#include "render/area_shaders.hpp"
#include "render/crs_cross_glsl.hpp"
#include "render/deferred_pass.hpp"
#include "render/gl_buffer.hpp"
#include "render/readback.hpp"
#include "render/tile_table.hpp"

namespace globe::viewer {

namespace {

constexpr float kTilePx = 256;  // tileformat §12.3: globe:tile_px

// Buffer bindings, as in area_shaders.hpp and kVectorPixelGlsl.
enum Binding : GLuint {
  kArena = 0,
  kRecords = 1,
  kTable = 2,
  kStyles = 3,
  kRequests = 4,
  kUsed = 5
};

}  // namespace

AreaRenderer::AreaRenderer(uint64_t arena_words, int width, int height, CrsCross cross)
    : cross_(cross) {
  program_ = GlProgram("area pass", kFullScreenVertex,
                       std::string(shaders::kAreaCommon) + shaders::kTileRefGlsl + kTileHashGlsl +
                           tile_table_glsl("line_table", kTable) + deferred_pass_glsl(kRequests) +
                           shaders::kCrsCrossGlsl + shaders::kVectorPixelGlsl +
                           shaders::kAreaFillFragment);
  GLuint buffers[6];
  gl::CreateBuffers(6, buffers);
  arena_ = buffers[0], records_ = buffers[1], table_ = buffers[2], styles_ = buffers[3],
  requests_ = buffers[4], used_ = buffers[5];
  gl::NamedBufferStorage(arena_, std::max<uint64_t>(arena_words, 4) * 4, nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
  gl::NamedBufferStorage(requests_, kRequestSlots * 2 * sizeof(uint32_t), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
  for (GLuint b : {records_, table_, styles_, used_})
    fill_buffer(b, 0, nullptr);
  gl::CreateVertexArrays(1, &vao_);
  gl::CreateQueries(GL_TIME_ELAPSED, 1, &timer_);
  resize(width, height);
  gl::check("creating the area renderer");
}

AreaRenderer::~AreaRenderer() {
  GLuint buffers[6] = {arena_, records_, table_, styles_, requests_, used_};
  gl::DeleteBuffers(6, buffers);
  gl::DeleteVertexArrays(1, &vao_);
  gl::DeleteFramebuffers(1, &fbo_);
  GLuint textures[3] = {output_, pixel_record_, pixel_polygon_};
  gl::DeleteTextures(3, textures);
  gl::DeleteQueries(1, &timer_);
}

void AreaRenderer::resize(int width, int height) {
  if (width == width_ && height == height_) return;
  width_ = width, height_ = height;
  if (fbo_) {
    gl::DeleteFramebuffers(1, &fbo_);
    GLuint textures[3] = {output_, pixel_record_, pixel_polygon_};
    gl::DeleteTextures(3, textures);
  }
  gl::CreateTextures(GL_TEXTURE_2D, 1, &output_);
  gl::TextureStorage2D(output_, 1, GL_RGBA8, width, height);
  for (GLuint* t : {&pixel_record_, &pixel_polygon_}) {
    gl::CreateTextures(GL_TEXTURE_2D, 1, t);
    gl::TextureStorage2D(*t, 1, GL_R32UI, width, height);
    gl::TextureParameteri(*t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl::TextureParameteri(*t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  gl::CreateFramebuffers(1, &fbo_);
  gl::NamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, output_, 0);
  gl::NamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT1, pixel_record_, 0);
  gl::NamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT2, pixel_polygon_, 0);
  const GLenum buffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
  gl::NamedFramebufferDrawBuffers(fbo_, 3, buffers);
}

void AreaRenderer::set_styles(const std::vector<AreaStyle>& classes) {
  std::vector<glm::vec4> v;
  for (const AreaStyle& c : classes) {
    v.push_back(c.fill);
    v.push_back(glm::vec4(c.outline, c.outline_px));
  }
  fill_buffer(styles_, v.size() * sizeof(glm::vec4), v.data());
  class_count_ = static_cast<int>(classes.size());
}

void AreaRenderer::upload(const AreaRecord& r) {
  if (r.tile.words.empty()) return;
  gl::NamedBufferSubData(arena_, r.offset * 4, r.tile.words.size() * 4, r.tile.words.data());
}

void AreaRenderer::upload_tables(const AreaCache& cache) {
  const auto& recs = cache.records();
  std::vector<glm::uvec4> gpu(recs.size() * 2, glm::uvec4(0));
  std::vector<std::pair<tileformat::TileId, uint32_t>> entries;
  for (uint32_t i = 0; i < recs.size(); ++i) {
    if (!cache.live(i)) continue;
    const AreaRecord& r = recs[i];
    const DecodedAreaTile& t = r.tile;
    entries.emplace_back(r.id, i);
    const uint32_t off = static_cast<uint32_t>(r.offset);
    gpu[2 * i] = {off, off + t.entries_at(), off + t.edge_refs_at(), t.grid};
    gpu[2 * i + 1] = {std::bit_cast<uint32_t>(float(t.extent)), off + t.edges_at(),
                      r.broken  ? 2u
                      : r.empty ? 1u
                                : 0u,
                      off + t.polygons_at()};
  }
  upload_vector_tables(records_, table_, used_, requests_, gpu, entries, table_mask_);
  record_count_ = static_cast<uint32_t>(recs.size());
}

double AreaRenderer::draw(const GBuffer& g, const View& view, const WorldFrame& world,
                          const AreaCache& cache, uint32_t frame, VectorFeedback& feedback) {
  upload_tables(cache);
  const tileformat::CommonMetadata& common = cache.package().meta.common;
  gl::BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  gl::Viewport(0, 0, width_, height_);
  gl::Disable(GL_DEPTH_TEST);
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, kArena, arena_);
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, kRecords, records_);
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, kTable, table_);
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, kStyles, styles_);
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, kRequests, requests_);
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, kUsed, used_);
  const GlProgram& p = program_;
  gl::UseProgram(p.id());
  bind_gbuffer(p, g);
  set_vector_pixel_uniforms(p, view, world, common.tiling, cross_, common.min_zoom, common.max_zoom,
                            kTilePx, lens_only_, height_);
  gl::Uniform1ui(p.uniform("line_table_mask"), table_mask_);
  gl::Uniform1ui(p.uniform("u_request_mask"), kRequestSlots - 1);
  gl::Uniform1ui(p.uniform("u_frame"), frame);
  gl::Uniform1i(p.uniform("u_class_count"), class_count_);
  gl::Uniform1i(p.uniform("u_select_only"), 0);
  gl::Uniform2f(p.uniform("u_area_ref"), float(kAreaRefX), float(kAreaRefY));
  gl::BindVertexArray(vao_);
  gl::BeginQuery(GL_TIME_ELAPSED, timer_);
  gl::DrawArrays(GL_TRIANGLES, 0, 3);
  gl::EndQuery(GL_TIME_ELAPSED);
  read_vector_feedback(
      requests_, used_, record_count_, frame, [&](uint32_t r) { return cache.live(r); }, feedback);
  GLuint64 ns = 0;
  gl::GetQueryObjectui64v(timer_, GL_QUERY_RESULT, &ns);
  gl::BindVertexArray(0);
  gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl::check("filling the areas");
  return static_cast<double>(ns) / 1e6;
}

std::pair<uint32_t, uint32_t> AreaRenderer::pick(int x, int y) const {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return {0, 0};
  return {read_u32(fbo_, 1, x, y, height_), read_u32(fbo_, 2, x, y, height_)};
}

}  // namespace globe::viewer
