// Terrain heights under key points (see key_heights.hpp).
#include "render/key_heights.hpp"

#include <utility>
#include <vector>

#include "render/gl_buffer.hpp"
#include "render/tile_table.hpp"

namespace globe::viewer {

void bind_key_heights(const GlProgram& p, GLuint table_buffer, int binding, const View& view,
                      const WorldFrame& world, const TerrainRenderer& terrain,
                      const TerrainHeights& heights, double exaggeration) {
  std::vector<std::pair<tileformat::TileId, uint32_t>> slots;
  for (const auto& [id, slot] : heights.slots)
    slots.emplace_back(id, static_cast<uint32_t>(slot));
  const auto table = build_tile_table(slots);
  fill_buffer(table_buffer, table.size() * sizeof(glm::uvec4), table.data());
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(binding), table_buffer);
  terrain.set_frame_uniforms(p, view, world, exaggeration);  // uses p
  gl::Uniform1ui(p.uniform("terrain_mask"), static_cast<uint32_t>(table.size() - 1));
  gl::Uniform2i(p.uniform("u_origin"), static_cast<int>(view.origin.x),
                static_cast<int>(view.origin.y));
  gl::Uniform3f(p.uniform("u_eye"), static_cast<float>(view.eye.x), static_cast<float>(view.eye.y),
                static_cast<float>(view.eye.z));
  gl::Uniform1i(p.uniform("u_tmin"), heights.min_zoom);
  gl::Uniform1i(p.uniform("u_tmax"), heights.max_zoom);
  gl::Uniform1i(p.uniform("u_key_zoom"), world.key_zoom());
  gl::Uniform1i(p.uniform("u_steps"), world.steps());
  gl::Uniform1f(p.uniform("u_block_size"), static_cast<float>(heights.block_size));
}

}  // namespace globe::viewer
