// The line pass (see line_renderer.hpp).
#include "render/line_renderer.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>

#include <glm/gtc/type_ptr.hpp>

#include "render/color.hpp"
#include "render/crs_cross_glsl.hpp"
#include "render/deferred_pass.hpp"
#include "render/gl_buffer.hpp"
#include "render/line_shaders.hpp"
#include "render/readback.hpp"
#include "render/terrain_shaders.hpp"
#include "render/tile_table.hpp"
#include "render/vector_pixel_glsl.hpp"

namespace globe::viewer {

namespace {

constexpr float kTilePx = 256;  // tileformat §7.3: draw tiles at >= 256 px per edge

// Buffer bindings, as in line_shaders.hpp.
enum Binding : GLuint {
  kArena = 0,
  kRecords = 1,
  kLineTable = 2,
  kStyles = 3,
  kRequests = 4,
  kUsed = 5,
  kTerrainTable = 6
};

// Where the view origin lies in tiles of zoom `zoom`, for tile_at() in GLSL.
void set_tile_ref(const GlProgram& p, const std::string& name, const View& view,
                  const WorldFrame& world, int zoom) {
  const tileformat::Tiling& t = world.tiling();
  const double size = t.tile_size(zoom);
  const glm::dvec2 o = world.key_to_crs(double(view.origin.x), double(view.origin.y));
  const double tx = (o.x - t.origin_x) / size, ty = (t.origin_y - o.y) / size;
  const double bx = std::floor(tx), by = std::floor(ty);
  gl::Uniform2i(p.uniform((name + ".base").c_str()), static_cast<int>(bx), static_cast<int>(by));
  gl::Uniform2f(p.uniform((name + ".frac").c_str()), static_cast<float>(tx - bx),
                static_cast<float>(ty - by));
  gl::Uniform2f(p.uniform((name + ".per_m").c_str()),
                static_cast<float>(1 / (world.ground_per_crs_x() * size)),
                static_cast<float>(1 / (world.ground_per_crs_y() * size)));
  gl::Uniform1i(p.uniform((name + ".zoom").c_str()), zoom);
  gl::Uniform1i(p.uniform((name + ".wrap").c_str()), t.wrap_tiles());
}

std::string program_source(const std::string& table, int binding, const std::string& body) {
  return std::string(shaders::kLineCommon) + shaders::kTileRefGlsl + kTileHashGlsl +
         tile_table_glsl(table, binding) + body;
}

}  // namespace

LineRenderer::LineRenderer(uint64_t arena_words, int width, int height, CrsCross cross)
    : cross_(cross) {
  deferred_ =
      GlProgram("line pass", kFullScreenVertex,
                program_source("line_table", kLineTable,
                               deferred_pass_glsl(kRequests) + shaders::kCrsCrossGlsl +
                                   shaders::kVectorPixelGlsl + shaders::kLineDeferredFragment));
  geometry_ =
      GlProgram("line geometry",
                program_source("terrain_table", kTerrainTable,
                               std::string(shaders::kLineQuadGlsl) + shaders::kLineGeometryVertex),
                shaders::kLineGeometryFragment);
  lifted_points_ = GlProgram::compute(
      "lifted line points",
      program_source("line_table", kLineTable,
                     tile_table_glsl("terrain", kTerrainTable) + shaders::kFrameWorldGlsl +
                         shaders::kKeyHeightGlsl + shaders::kLineLiftedPoints));
  lifted_ = GlProgram("lifted lines",
                      std::string(shaders::kLineCommon) + shaders::kTileRefGlsl +
                          shaders::kLineQuadGlsl + shaders::kLineLiftedVertex,
                      shaders::kLineLiftedFragment);
  GLuint buffers[9];
  gl::CreateBuffers(9, buffers);
  arena_ = buffers[0], records_ = buffers[1], table_ = buffers[2], styles_ = buffers[3],
  requests_ = buffers[4], used_ = buffers[5], terrain_table_ = buffers[6], points_ = buffers[7],
  items_ = buffers[8];
  gl::NamedBufferStorage(arena_, std::max<uint64_t>(arena_words, 4) * 4, nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
  gl::NamedBufferStorage(requests_, kRequestSlots * 2 * sizeof(uint32_t), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
  for (GLuint b : {records_, table_, styles_, used_, terrain_table_, points_, items_})
    fill_buffer(b, 0, nullptr);
  gl::CreateVertexArrays(1, &vao_);
  gl::CreateQueries(GL_TIME_ELAPSED, 1, &timer_);
  resize(width, height);
  gl::check("creating the line renderer");
}

LineRenderer::~LineRenderer() {
  GLuint buffers[9] = {arena_, records_,       table_,  styles_, requests_,
                       used_,  terrain_table_, points_, items_};
  gl::DeleteBuffers(9, buffers);
  gl::DeleteVertexArrays(1, &vao_);
  GLuint fbos[2] = {fbo_, geometry_fbo_}, textures[3] = {output_, pixel_record_, pixel_segment_};
  gl::DeleteFramebuffers(2, fbos);
  gl::DeleteTextures(3, textures);
  gl::DeleteQueries(1, &timer_);
  if (ramps_) gl::DeleteTextures(1, &ramps_);
}

void LineRenderer::resize(int width, int height) {
  if (width == width_ && height == height_) return;
  width_ = width, height_ = height;
  if (fbo_) {
    GLuint fbos[2] = {fbo_, geometry_fbo_}, textures[3] = {output_, pixel_record_, pixel_segment_};
    gl::DeleteFramebuffers(2, fbos);
    gl::DeleteTextures(3, textures);
  }
  gl::CreateTextures(GL_TEXTURE_2D, 1, &output_);
  gl::TextureStorage2D(output_, 1, GL_RGBA8, width, height);
  for (GLuint* t : {&pixel_record_, &pixel_segment_}) {
    gl::CreateTextures(GL_TEXTURE_2D, 1, t);
    gl::TextureStorage2D(*t, 1, GL_R32UI, width, height);
    gl::TextureParameteri(*t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);  // complete without mipmaps
    gl::TextureParameteri(*t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  gl::CreateFramebuffers(1, &fbo_);
  gl::NamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, output_, 0);
  gl::NamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT1, pixel_record_, 0);
  gl::NamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT2, pixel_segment_, 0);
  const GLenum buffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
  gl::NamedFramebufferDrawBuffers(fbo_, 3, buffers);
  gl::CreateFramebuffers(1, &geometry_fbo_);
  gl::NamedFramebufferTexture(geometry_fbo_, GL_COLOR_ATTACHMENT0, output_, 0);
}

void LineRenderer::set_styles(const std::vector<NamedLineStyle>& classes,
                              const std::vector<LineRamp>& ramps) {
  std::vector<glm::vec4> v;
  std::vector<uint8_t> rows;
  for (size_t k = 0; k < classes.size(); ++k) {
    const NamedLineStyle& c = classes[k];
    const LineStyle& s = c.style;
    const bool casing = !s.casing_color.empty() && s.casing_width > 0;
    float dash[8] = {};
    for (size_t i = 0; i < s.dash.size() && i < 8; ++i)
      dash[i] = static_cast<float>(s.dash[i]);
    glm::vec4 fill = hex_rgba(s.color);
    fill.a = static_cast<float>(std::clamp(s.opacity, 0.0, 1.0));
    v.push_back(fill);
    v.push_back(casing ? hex_rgba(s.casing_color) : glm::vec4(0));
    v.push_back({s.visible ? s.width / 2 : 0.0, casing ? s.casing_width : 0.0,
                 s.width_in_m ? 1.0 : 0.0, static_cast<float>(s.dash.size())});
    v.push_back({dash[0], dash[1], dash[2], dash[3]});
    v.push_back({dash[4], dash[5], dash[6], dash[7]});
    const int pattern = std::max(line_pattern_id(s.pattern), 0);
    v.push_back({float(pattern), pattern ? float(line_pattern_spacing(s)) : 0.0f, 0.0f, 0.0f});
    const LineRamp* r = k < ramps.size() && ramps[k].by > 0 ? &ramps[k] : nullptr;
    const int row = static_cast<int>(rows.size() / (LineRamp::kEntries * 4));
    if (r) rows.insert(rows.end(), r->rgba.begin(), r->rgba.end());
    v.push_back({r ? float(r->by) : 0.0f, float(row), r ? r->lo : 0.0f, r ? r->hi : 1.0f});
  }
  if (ramps_) gl::DeleteTextures(1, &ramps_);
  ramp_rows_ = std::max<int>(1, static_cast<int>(rows.size() / (LineRamp::kEntries * 4)));
  rows.resize(size_t(ramp_rows_) * LineRamp::kEntries * 4, 0);
  gl::CreateTextures(GL_TEXTURE_2D, 1, &ramps_);
  gl::TextureStorage2D(ramps_, 1, GL_RGBA8, LineRamp::kEntries, ramp_rows_);
  gl::TextureParameteri(ramps_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl::TextureParameteri(ramps_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl::TextureParameteri(ramps_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl::TextureParameteri(ramps_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  gl::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl::TextureSubImage2D(ramps_, 0, 0, 0, LineRamp::kEntries, ramp_rows_, GL_RGBA, GL_UNSIGNED_BYTE,
                        rows.data());
  fill_buffer(styles_, v.size() * sizeof(glm::vec4), v.data());
  class_count_ = static_cast<int>(classes.size());
  // Lifted lines: narrower classes first, so wider ones lie on top (where
  // the deferred pass lets the higher coverage win), then by class id.
  lifted_order_.resize(classes.size());
  for (size_t i = 0; i < classes.size(); ++i)
    lifted_order_[i] = static_cast<int>(i);
  std::stable_sort(lifted_order_.begin(), lifted_order_.end(), [&](int a, int b) {
    const auto extent = [&](int c) {
      const LineStyle& s = classes[size_t(c)].style;
      return s.visible ? s.half_extent() : 0.0;
    };
    return extent(a) < extent(b);
  });
}

void LineRenderer::upload(uint32_t index, const LineRecord& r) {
  std::vector<uint16_t>& classes = segment_classes_[index];
  classes.clear();
  if (r.tile.words.empty()) return;
  gl::NamedBufferSubData(arena_, r.offset * 4, r.tile.words.size() * 4, r.tile.words.data());
  const size_t segs = size_t(r.tile.grid) * r.tile.grid + 1 + r.tile.cell_entries;
  for (uint32_t s = 0; s < r.tile.segments; ++s)
    classes.push_back(static_cast<uint16_t>(r.tile.words[segs + size_t(s) * 6 + 4]));
}

void LineRenderer::upload_tables(const LineCache& cache) {
  const auto& recs = cache.records();
  std::vector<glm::uvec4> gpu(recs.size() * 2, glm::uvec4(0));
  std::vector<std::pair<tileformat::TileId, uint32_t>> entries;
  for (uint32_t i = 0; i < recs.size(); ++i) {
    if (!cache.live(i)) continue;
    const LineRecord& r = recs[i];
    entries.emplace_back(r.id, i);
    const uint32_t cells = r.tile.grid * r.tile.grid + 1;
    const uint32_t off = static_cast<uint32_t>(r.offset);
    gpu[2 * i] = {off, off + cells, off + cells + r.tile.cell_entries, r.tile.grid};
    gpu[2 * i + 1] = {std::bit_cast<uint32_t>(float(r.tile.extent)),
                      std::bit_cast<uint32_t>(float(r.tile.reach)),
                      r.broken  ? 2u
                      : r.empty ? 1u
                                : 0u,
                      0u};
  }
  upload_vector_tables(records_, table_, used_, requests_, gpu, entries, table_mask_);
  record_count_ = static_cast<uint32_t>(recs.size());
}

double LineRenderer::draw(const GBuffer& g, const View& view, const WorldFrame& world,
                          double exaggeration, const LineCache& cache,
                          const TerrainHeights& terrain, LineMode mode, uint32_t frame,
                          LineFeedback& feedback) {
  upload_tables(cache);
  const LinePackage& pkg = cache.package();
  const tileformat::Tiling& tiling = pkg.tiling;

  gl::BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  gl::Viewport(0, 0, width_, height_);
  gl::Disable(GL_DEPTH_TEST);
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, kArena, arena_);
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, kRecords, records_);
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, kLineTable, table_);
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, kStyles, styles_);
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, kRequests, requests_);
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, kUsed, used_);

  const GlProgram& p = deferred_;
  gl::UseProgram(p.id());
  bind_gbuffer(p, g);
  gl::BindTextureUnit(5, ramps_);
  gl::Uniform1i(p.uniform("u_line_ramps"), 5);
  set_vector_pixel_uniforms(p, view, world, tiling, cross_, pkg.min_zoom, pkg.max_zoom, kTilePx,
                            lens_only_, height_);
  gl::Uniform1f(p.uniform("u_units_to_nominal_px"), kTilePx / float(std::max(pkg.extent, 1)));
  gl::Uniform1f(p.uniform("u_world_per_m"), static_cast<float>(world.ground_height_scale()));
  gl::Uniform1ui(p.uniform("line_table_mask"), table_mask_);
  gl::Uniform1ui(p.uniform("u_request_mask"), kRequestSlots - 1);
  gl::Uniform1ui(p.uniform("u_frame"), frame);
  gl::Uniform1i(p.uniform("u_class_count"), class_count_);
  gl::Uniform1i(p.uniform("u_select_only"), mode == LineMode::kDeferred ? 0 : 1);
  gl::BindVertexArray(vao_);
  if (mode == LineMode::kDeferred) gl::BeginQuery(GL_TIME_ELAPSED, timer_);
  gl::DrawArrays(GL_TRIANGLES, 0, 3);
  if (mode == LineMode::kDeferred) gl::EndQuery(GL_TIME_ELAPSED);
  read_feedback(cache, frame, feedback);
  if (mode == LineMode::kGeometry) {
    gl::BeginQuery(GL_TIME_ELAPSED, timer_);
    draw_geometry(view, world, exaggeration, cache, terrain, g.depth, feedback.used);
    gl::EndQuery(GL_TIME_ELAPSED);
  } else if (mode == LineMode::kLifted) {
    gl::BeginQuery(GL_TIME_ELAPSED, timer_);
    draw_lifted(view, world, exaggeration, cache, terrain, g.depth, feedback.used, frame);
    gl::EndQuery(GL_TIME_ELAPSED);
  }
  GLuint64 ns = 0;
  gl::GetQueryObjectui64v(timer_, GL_QUERY_RESULT, &ns);
  gl::BindVertexArray(0);
  gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl::check("drawing the lines");
  return static_cast<double>(ns) / 1e6;
}

std::pair<uint32_t, uint32_t> LineRenderer::pick(int x, int y) const {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return {0, 0};
  return {read_u32(fbo_, 1, x, y, height_), read_u32(fbo_, 2, x, y, height_)};
}

void LineRenderer::read_feedback(const LineCache& cache, uint32_t frame, LineFeedback& fb) {
  read_vector_feedback(
      requests_, used_, record_count_, frame, [&](uint32_t r) { return cache.live(r); }, fb);
}

uint32_t LineRenderer::upload_terrain_table(const TerrainHeights& terrain) {
  std::vector<std::pair<tileformat::TileId, uint32_t>> slots;
  for (const auto& [id, slot] : terrain.slots)
    slots.emplace_back(id, static_cast<uint32_t>(slot));
  const auto table = build_tile_table(slots);
  fill_buffer(terrain_table_, table.size() * sizeof(glm::uvec4), table.data());
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, kTerrainTable, terrain_table_);
  return static_cast<uint32_t>(table.size() - 1);
}

void LineRenderer::draw_geometry(const View& view, const WorldFrame& world, double exaggeration,
                                 const LineCache& cache, const TerrainHeights& terrain,
                                 GLuint depth, const std::vector<uint32_t>& used) {
  const uint32_t terrain_mask = upload_terrain_table(terrain);

  gl::NamedFramebufferTexture(geometry_fbo_, GL_DEPTH_ATTACHMENT, depth, 0);
  gl::BindFramebuffer(GL_FRAMEBUFFER, geometry_fbo_);
  const GlProgram& p = geometry_;
  gl::UseProgram(p.id());
  gl::BindTextureUnit(4, pixel_record_);
  gl::Uniform1i(p.uniform("u_pixel_record"), 4);
  gl::BindTextureUnit(3, terrain.texture);
  gl::Uniform1i(p.uniform("u_heights"), 3);
  gl::Uniform1ui(p.uniform("terrain_table_mask"), terrain_mask);
  set_tile_ref(p, "u_terrain_ref", view, world, terrain.max_zoom);
  gl::Uniform1i(p.uniform("u_terrain_min_zoom"), terrain.min_zoom);
  gl::Uniform1i(p.uniform("u_terrain_max_zoom"), terrain.max_zoom);
  gl::Uniform1f(p.uniform("u_block_steps"), float(terrain.block_size - 1));
  gl::Uniform1f(p.uniform("u_block_size"), float(terrain.block_size));
  gl::Uniform1f(p.uniform("u_zscale"), float(world.ground_height_scale() * exaggeration));
  gl::UniformMatrix4fv(p.uniform("u_view_proj"), 1, GL_FALSE, glm::value_ptr(view.view_proj));
  gl::Uniform2f(p.uniform("u_viewport"), float(width_), float(height_));
  gl::Uniform1f(p.uniform("u_focal_px"), float(height_ * 0.5 * view.proj[1][1]));
  gl::Uniform1i(p.uniform("u_class_count"), class_count_);
  gl::Uniform1f(p.uniform("u_world_per_m"), static_cast<float>(world.ground_height_scale()));

  gl::Enable(GL_DEPTH_TEST);
  gl::DepthFunc(GL_LEQUAL);
  gl::DepthMask(GL_FALSE);
  gl::Enable(GL_POLYGON_OFFSET_FILL);
  gl::PolygonOffset(-1.0f, -4.0f);
  const tileformat::Tiling& tiling = world.tiling();
  const glm::dvec2 o = world.key_to_crs(double(view.origin.x), double(view.origin.y));
  const double mx = world.ground_per_crs_x(), my = world.ground_per_crs_y();
  for (int layer = 0; layer < 2; ++layer) {
    gl::Uniform1i(p.uniform("u_layer"), layer);
    for (uint32_t r : used) {
      const LineRecord& rec = cache.records()[r];
      if (rec.empty || rec.tile.segments == 0) continue;
      const double size = tiling.tile_size(rec.id.z);
      const double cx = tiling.origin_x + rec.id.x * size, cy = tiling.origin_y - rec.id.y * size;
      const uint32_t cells = rec.tile.grid * rec.tile.grid + 1;
      gl::Uniform1ui(p.uniform("u_segs_base"),
                     static_cast<uint32_t>(rec.offset) + cells + rec.tile.cell_entries);
      gl::Uniform2f(p.uniform("u_tile_origin"), float((cx - o.x) * mx), float((cy - o.y) * my));
      gl::Uniform2f(p.uniform("u_m_per_unit"), float(mx * size / rec.tile.extent),
                    float(my * size / rec.tile.extent));
      gl::Uniform1ui(p.uniform("u_record"), r);
      gl::DrawArraysInstanced(GL_TRIANGLES, 0, 6, static_cast<GLsizei>(rec.tile.segments));
    }
  }
  gl::Disable(GL_POLYGON_OFFSET_FILL);
  gl::DepthMask(GL_TRUE);
  gl::Disable(GL_DEPTH_TEST);
}

void LineRenderer::draw_lifted(const View& view, const WorldFrame& world, double exaggeration,
                               const LineCache& cache, const TerrainHeights& terrain, GLuint depth,
                               const std::vector<uint32_t>& used, uint32_t frame) {
  if (!terrain.frame) throw std::logic_error("lifted lines without the terrain's frame");
  constexpr int kPieces = 8;
  const uint32_t terrain_mask = upload_terrain_table(terrain);

  // Where each chosen tile's points go, and the items of each class.
  struct Tile {
    uint32_t record, first_point;
  };
  std::vector<Tile> tiles;
  std::vector<std::vector<glm::uvec2>> items(static_cast<size_t>(class_count_));
  uint32_t points = 0;
  for (uint32_t r : used) {
    const LineRecord& rec = cache.records()[r];
    const auto classes = segment_classes_.find(r);
    if (rec.empty || rec.tile.segments == 0 || classes == segment_classes_.end()) continue;
    tiles.push_back({r, points});
    for (uint32_t s = 0; s < rec.tile.segments; ++s) {
      const uint16_t c = classes->second[s];
      if (c < class_count_) items[c].push_back({points + s * (kPieces + 1), c});
    }
    points += rec.tile.segments * (kPieces + 1);
  }
  if (points == 0) return;
  if (points > points_capacity_) {
    points_capacity_ = std::max<size_t>(points, points_capacity_ * 2);
    gl::NamedBufferData(points_, points_capacity_ * sizeof(glm::vec4), nullptr, GL_DYNAMIC_COPY);
  }
  std::vector<glm::uvec2> all;
  std::vector<std::pair<uint32_t, uint32_t>> range(static_cast<size_t>(class_count_));  // items
  for (int c = 0; c < class_count_; ++c) {
    range[size_t(c)] = {static_cast<uint32_t>(all.size()),
                        static_cast<uint32_t>(items[size_t(c)].size())};
    all.insert(all.end(), items[size_t(c)].begin(), items[size_t(c)].end());
  }
  fill_buffer(items_, all.size() * sizeof(glm::uvec2), all.data());
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, points_);
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, items_);

  // 1. The lifted points of every chosen tile.
  const GlProgram& c = lifted_points_;
  terrain.frame->set_frame_uniforms(c, view, world, exaggeration);  // uses c
  gl::Uniform1ui(c.uniform("terrain_mask"), terrain_mask);
  gl::Uniform1ui(c.uniform("line_table_mask"), table_mask_);
  gl::Uniform1i(c.uniform("u_tmin"), terrain.min_zoom);
  gl::Uniform1i(c.uniform("u_tmax"), terrain.max_zoom);
  gl::Uniform1i(c.uniform("u_key_zoom"), world.key_zoom());
  gl::Uniform1i(c.uniform("u_steps"), world.steps());
  gl::Uniform1f(c.uniform("u_block_size"), float(terrain.block_size));
  gl::Uniform2i(c.uniform("u_origin"), static_cast<int>(view.origin.x),
                static_cast<int>(view.origin.y));
  gl::Uniform1f(c.uniform("u_focal_px"), float(height_ * 0.5 * view.proj[1][1]));
  gl::Uniform1ui(c.uniform("u_frame"), frame);
  gl::Uniform1i(c.uniform("u_max_zoom"), cache.package().max_zoom);
  gl::Uniform1f(c.uniform("u_lift"), static_cast<float>(terrain.lift_m * world.height_scale()));
  gl::Uniform1f(c.uniform("u_error_px"), static_cast<float>(terrain.error_px));
  gl::Uniform3f(c.uniform("u_eye"), float(view.eye.x), float(view.eye.y), float(view.eye.z));
  gl::Uniform1i(c.uniform("u_pieces"), kPieces);
  for (const Tile& t : tiles) {
    const LineRecord& rec = cache.records()[t.record];
    // The tile's origin and scale in key units (its zoom may be finer or
    // coarser than the terrain's finest, the key zoom).
    const double keys = std::ldexp(double(world.steps()), world.key_zoom() - rec.id.z);
    const uint32_t cells = rec.tile.grid * rec.tile.grid + 1;
    const uint32_t count = rec.tile.segments * (kPieces + 1);
    gl::Uniform1ui(c.uniform("u_segs_base"),
                   static_cast<uint32_t>(rec.offset) + cells + rec.tile.cell_entries);
    gl::Uniform1ui(c.uniform("u_points_base"), t.first_point);
    gl::Uniform1ui(c.uniform("u_point_count"), count);
    gl::Uniform1i(c.uniform("u_zoom"), rec.id.z);
    gl::Uniform2i(c.uniform("u_tile"), static_cast<int>(rec.id.x), static_cast<int>(rec.id.y));
    gl::Uniform1f(c.uniform("u_extent"), float(rec.tile.extent));
    gl::Uniform2f(c.uniform("u_tile_key"), float(rec.id.x * keys - double(view.origin.x)),
                  float(rec.id.y * keys - double(view.origin.y)));
    gl::Uniform1f(c.uniform("u_keys_per_unit"), float(keys / rec.tile.extent));
    // Heights from a ring of half the longest piece of the tile (at least 2
    // px of its nominal 256) around each point.
    const double ring = std::max(1.0 / 128, rec.tile.longest / (2.0 * kPieces) / rec.tile.extent);
    gl::Uniform1f(c.uniform("u_ring_keys"), float(keys * ring));
    gl::DispatchCompute((count + 63) / 64, 1, 1);
  }
  gl::MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

  // 2. Per layer and class (casings under fills, classes in lifted_order_),
  // the pieces of that class's segments.
  gl::NamedFramebufferTexture(geometry_fbo_, GL_DEPTH_ATTACHMENT, depth, 0);
  gl::BindFramebuffer(GL_FRAMEBUFFER, geometry_fbo_);
  const GlProgram& p = lifted_;
  gl::UseProgram(p.id());
  gl::UniformMatrix4fv(p.uniform("u_view_proj"), 1, GL_FALSE, glm::value_ptr(view.view_proj));
  gl::Uniform2f(p.uniform("u_viewport"), float(width_), float(height_));
  gl::Uniform1f(p.uniform("u_focal_px"), float(height_ * 0.5 * view.proj[1][1]));
  gl::Uniform1i(p.uniform("u_class_count"), class_count_);
  gl::Uniform1f(p.uniform("u_world_per_m"), static_cast<float>(world.ground_height_scale()));
  gl::Uniform1i(p.uniform("u_pieces"), kPieces);
  gl::Enable(GL_DEPTH_TEST);
  gl::DepthFunc(GL_LEQUAL);
  gl::DepthMask(GL_FALSE);
  for (int pass = 0; pass < 2 * class_count_; ++pass) {
    const auto [first, count] = range[size_t(lifted_order_[size_t(pass % class_count_)])];
    if (count == 0) continue;
    gl::Uniform1i(p.uniform("u_layer"), pass / class_count_);
    gl::Uniform1ui(p.uniform("u_item_base"), first);
    gl::DrawArraysInstanced(GL_TRIANGLES, 0, 6, static_cast<GLsizei>(count * kPieces));
  }
  gl::DepthMask(GL_TRUE);
  gl::Disable(GL_DEPTH_TEST);
}

}  // namespace globe::viewer
