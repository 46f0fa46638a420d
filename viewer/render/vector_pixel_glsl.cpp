// Uniforms of the per-pixel vector passes (see vector_pixel_glsl.hpp).
#include "render/vector_pixel_glsl.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/type_ptr.hpp>

#include "render/crs_cross_glsl.hpp"
#include "render/deferred_pass.hpp"
#include "render/gl_buffer.hpp"
#include "render/tile_table.hpp"

namespace globe::viewer {

void read_vector_feedback(GLuint requests, GLuint used, uint32_t records, uint32_t frame,
                          const std::function<bool(uint32_t)>& live, VectorFeedback& out) {
  gl::MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<uint32_t> req(kRequestSlots * 2), stamps(records);
  gl::GetNamedBufferSubData(requests, 0, req.size() * 4, req.data());
  if (records) gl::GetNamedBufferSubData(used, 0, stamps.size() * 4, stamps.data());
  out.requests.clear();
  out.used.clear();
  for (const TileRequest& r : decode_tile_requests(req))
    out.requests.push_back(r.id);
  for (uint32_t r = 0; r < records; ++r)
    if (stamps[r] == frame && live(r)) out.used.push_back(r);
}

void bind_gbuffer(const GlProgram& p, const GBuffer& g) {
  gl::BindTextureUnit(0, g.color);
  gl::BindTextureUnit(1, g.position);
  gl::BindTextureUnit(2, g.ground);
  gl::BindTextureUnit(3, g.ground_dy);
  gl::Uniform1i(p.uniform("u_color"), 0);
  gl::Uniform1i(p.uniform("u_position"), 1);
  gl::Uniform1i(p.uniform("u_ground"), 2);
  gl::Uniform1i(p.uniform("u_ground_dy"), 3);
}

void upload_vector_tables(GLuint records, GLuint table, GLuint used, GLuint requests,
                          const std::vector<glm::uvec4>& words,
                          const std::vector<std::pair<tileformat::TileId, uint32_t>>& entries,
                          uint32_t& table_mask) {
  fill_buffer(records, words.size() * sizeof(glm::uvec4), words.data());
  const auto hash = build_tile_table(entries);
  fill_buffer(table, hash.size() * sizeof(glm::uvec4), hash.data());
  table_mask = static_cast<uint32_t>(hash.size() - 1);
  const size_t count = words.size() / 2;
  const std::vector<uint32_t> zeros(std::max<size_t>(count, kRequestSlots * 2), 0);
  fill_buffer(used, count * sizeof(uint32_t), zeros.data());
  gl::NamedBufferSubData(requests, 0, kRequestSlots * 2 * sizeof(uint32_t), zeros.data());
}

void set_vector_ref(const GlProgram& p, const View& view, const WorldFrame& world,
                    const tileformat::Tiling& lt, CrsCross cross, int zoom) {
  const glm::dvec2 o = world.key_to_crs(double(view.origin.x), double(view.origin.y));
  const CrossAnchor a = cross_anchor(cross, o);
  const double size = lt.tile_size(zoom);
  const double tx = (a.anchor.x - lt.origin_x) / size, ty = (lt.origin_y - a.anchor.y) / size;
  const double bx = std::floor(tx), by = std::floor(ty);
  gl::Uniform2i(p.uniform("u_ref.base"), static_cast<int>(bx), static_cast<int>(by));
  gl::Uniform2f(p.uniform("u_ref.frac"), static_cast<float>(tx - bx), static_cast<float>(ty - by));
  const bool same = cross == CrsCross::kSame;
  gl::Uniform2f(p.uniform("u_ref.per_m"),
                static_cast<float>(1 / ((same ? world.ground_per_crs_x() : 1.0) * size)),
                static_cast<float>(1 / ((same ? world.ground_per_crs_y() : 1.0) * size)));
  gl::Uniform1i(p.uniform("u_ref.zoom"), zoom);
  gl::Uniform1i(p.uniform("u_ref.wrap"), lt.wrap_tiles());
  gl::Uniform1i(p.uniform("u_cross"), static_cast<int>(cross));
  gl::Uniform2f(p.uniform("u_cross_param"), a.param.x, a.param.y);
  gl::Uniform2f(p.uniform("u_crs_per_m"), static_cast<float>(1 / world.ground_per_crs_x()),
                static_cast<float>(1 / world.ground_per_crs_y()));
}

void set_vector_pixel_uniforms(const GlProgram& p, const View& view, const WorldFrame& world,
                               const tileformat::Tiling& lt, CrsCross cross, int min_zoom,
                               int max_zoom, float tile_px, const glm::vec3& lens, int height) {
  const glm::mat4 inv = glm::mat4(glm::inverse(view.proj * view.view));
  gl::UniformMatrix4fv(p.uniform("u_inv_view_proj"), 1, GL_FALSE, glm::value_ptr(inv));
  gl::Uniform3f(p.uniform("u_eye"), float(view.eye.x), float(view.eye.y), float(view.eye.z));
  set_vector_ref(p, view, world, lt, cross, max_zoom);
  gl::Uniform1i(p.uniform("u_min_zoom"), min_zoom);
  gl::Uniform1i(p.uniform("u_max_zoom"), max_zoom);
  const double m0x = world.ground_per_crs_x() * lt.root_size,
               m0y = world.ground_per_crs_y() * lt.root_size;
  gl::Uniform1f(p.uniform("u_zoom_bias"),
                static_cast<float>(std::log2(std::min(m0x, m0y) / tile_px)));
  gl::Uniform2f(p.uniform("u_tile_m0"), float(m0x), float(m0y));
  gl::Uniform3f(p.uniform("u_lens_only"), lens.x, float(height) - lens.y, lens.z);
}

}  // namespace globe::viewer
