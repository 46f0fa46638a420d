// What the per-pixel passes over vector tiles share (the line pass and the
// area fill pass, docs/viewer.md "Lines", "Areas"): tile coordinates of
// world points (TileRef), and per pixel of the G-buffer the ground point, its
// Jacobian, the zoom its footprint wants and the tile record drawn there -
// the wanted tile, else the coarser ones, and past a broken tile the finer
// ones under it - with the requests for missing tiles. C++ side: the
// uniforms (set_vector_ref, set_vector_pixel_uniforms).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "camera/camera.hpp"
#include "camera/layer_tiling.hpp"
#include "camera/world_frame.hpp"
#include "render/gl_program.hpp"
#include "render/terrain_renderer.hpp"
#include "tileformat/tiling.hpp"

namespace globe::viewer {

namespace shaders {

// Tile coordinates of world points: `base + frac` is the view origin in
// tiles of zoom `zoom`, `per_m` tiles per world metre (x east, y north),
// `wrap` tiles across 360 degrees at zoom 0 (0: a tiling that does not wrap;
// on the globe, ground points continue past the antimeridian).
inline constexpr const char* kTileRefGlsl = R"(
struct TileRef {
  ivec2 base;
  vec2 frac;
  vec2 per_m;
  int zoom;
  int wrap;
};
// The tile of zoom z (<= ref.zoom) holding the point p tiles of zoom
// ref.zoom from ref.base (y south), and p's position inside it (0..1, y south).
ivec2 tile_of(TileRef r, int z, vec2 p, out vec2 local) {
  vec2 fl = floor(p);
  ivec2 g = r.base + ivec2(fl);
  int s = r.zoom - z;
  ivec2 t = g >> s;
  local = (vec2(g - (t << s)) + (p - fl)) / float(1 << s);
  if (r.wrap > 0) {
    int n = r.wrap << z;
    t.x = ((t.x % n) + n) % n;
  }
  return t;
}
// The same for world point w.
ivec2 tile_at(TileRef r, int z, vec2 w, out vec2 local) {
  return tile_of(r, z, r.frac + vec2(w.x, -w.y) * r.per_m, local);
}
)";

// After kTileRefGlsl, the tile hash, the record table `line_table`,
// deferred_pass_glsl() and kCrsCrossGlsl. Records: 2 uvec4 per record, the
// second's z a flag (0 drawn, 1 empty, 2 broken).
inline constexpr const char* kVectorPixelGlsl = R"(
layout(std430, binding = 1) readonly buffer Records { uvec4 records[]; };  // 2 per record
layout(std430, binding = 5) buffer Used { uint used[]; };
uniform uint u_frame;
uniform sampler2D u_ground, u_ground_dy;
uniform vec3 u_lens_only;  // drawn only inside this circle (window pixels; radius 0: everywhere)
uniform TileRef u_ref;     // the layer tiling's (per_m: per layer CRS unit when crossing)
uniform int u_cross;       // 0 the terrain's CRS, 1/2 crossing (kCrsCrossGlsl)
uniform vec2 u_cross_param, u_crs_per_m;  // crossing: its parameter, terrain CRS units per ground unit
uniform int u_min_zoom, u_max_zoom;
uniform float u_zoom_bias;  // log2(shorter zoom-0 tile edge in world metres / tile_px)
uniform vec2 u_tile_m0;     // world metres per tile edge at zoom 0 (x, y)

struct VectorPixel {
  mat2 J, Jinv;            // ground metres per screen pixel (x, y), and back
  int wanted, z, zz, rec;  // zoom the footprint wants, that clamped, the zoom drawn, its record
  vec2 local;              // the pixel in the drawn tile (0..1, y south)
  mat2 L;                  // ground metres per tile unit of the drawn tile (x east, y south)
};

// The pixel's record (v.rec, -1: none; it may be empty), or false where the
// pixel shows no ground, lies outside the lens or past the crossing's edge.
bool vector_pixel(ivec2 px, out VectorPixel v) {
  v.rec = -1;
  vec4 p4 = texelFetch(u_position, px, 0);
  if (p4.w == 0.0) return false;
  if (u_lens_only.z > 0.0 && distance(gl_FragCoord.xy, u_lens_only.xy) >= u_lens_only.z)
    return false;
  // The pixel's ground point and its screen derivatives (terrain_renderer.hpp).
  vec4 gr = texelFetch(u_ground, px, 0);
  vec2 G = gr.xy;
  v.J = mat2(gr.zw, texelFetch(u_ground_dy, px, 0).xy);
  if (abs(determinant(v.J)) < 1e-12) return false;
  v.Jinv = inverse(v.J);
  // The zoom follows the pixel's area footprint (sqrt |det J|); in oblique
  // views that is finer than the most stretched direction would allow.
  float footprint = sqrt(abs(determinant(v.J)));
  // The pixel in tiles of the layer tiling's zoom u_ref.zoom (p), and ground
  // metres per such tile (M, columns x east and y south): linear in the
  // terrain's CRS, through the crossing's Jacobian at the pixel otherwise.
  vec2 p;
  mat2 M;
  float zoom_bias = u_zoom_bias;
  if (u_cross == 0) {
    p = u_ref.frac + vec2(G.x, -G.y) * u_ref.per_m;
    M = mat2(1.0 / u_ref.per_m.x, 0.0, 0.0, -1.0 / u_ref.per_m.y);
  } else {
    vec2 c0, c1, c2;
    if (!cross_offset(u_cross, u_cross_param, G * u_crs_per_m, c0)) return false;  // past its edge
    cross_offset(u_cross, u_cross_param, (G + v.J[0]) * u_crs_per_m, c1);
    cross_offset(u_cross, u_cross_param, (G + v.J[1]) * u_crs_per_m, c2);
    vec2 flip = vec2(1, -1) * u_ref.per_m;
    p = u_ref.frac + c0 * flip;
    mat2 Jt = mat2((c1 - c0) * flip, (c2 - c0) * flip);  // tiles per pixel
    if (abs(determinant(Jt)) < 1e-30) return false;
    M = v.J * inverse(Jt);
    zoom_bias = log2(min(length(M[0]), length(M[1])) / 256.0) + float(u_ref.zoom);
  }
  v.wanted = int(floor(zoom_bias - log2(footprint)));  // may lie past the package's zooms
  v.z = clamp(v.wanted, u_min_zoom, u_max_zoom);
  // The wanted tile, else the coarser ones. Past a broken tile (record flag
  // 2) the next coarser unknown one is asked for too; where no coarser tile
  // can be drawn, the finer ones under the broken tile are (one or two zooms
  // down).
  int broken_z = -1;
  bool ask = true;
  for (v.zz = v.z; v.zz >= u_min_zoom; --v.zz) {
    ivec2 t = tile_of(u_ref, v.zz, p, v.local);
    v.rec = line_table_lookup(v.zz, t);
    if (v.rec >= 0 && records[2 * v.rec + 1].z == 2u) {
      if (broken_z < 0) broken_z = v.zz;
      v.rec = -1;
      ask = true;
      continue;
    }
    if (v.rec >= 0) break;
    if (ask) request(v.zz, t, 0u);
    ask = false;
  }
  for (int zf = broken_z + 1; v.rec < 0 && broken_z >= 0 && zf <= min(broken_z + 2, u_max_zoom);
       ++zf) {
    ivec2 tf = tile_of(u_ref, zf, p, v.local);
    int r = line_table_lookup(zf, tf);
    if (r < 0) request(zf, tf, 0u);
    if (r < 0 || records[2 * r + 1].z == 1u) break;
    if (records[2 * r + 1].z == 0u) v.rec = r, v.zz = zf;
  }
  if (v.rec >= 0) {
    float extent = uintBitsToFloat(records[2 * v.rec + 1].x);
    v.L = u_cross == 0 ? mat2(u_tile_m0.x / (exp2(float(v.zz)) * extent), 0.0, 0.0,
                              -u_tile_m0.y / (exp2(float(v.zz)) * extent))
                       : M * (exp2(float(u_ref.zoom - v.zz)) / extent);
  }
  return true;
}
)";

}  // namespace shaders

// What a frame's pixels asked for and used.
struct VectorFeedback {
  std::vector<tileformat::TileId> requests;  // wanted, not resident
  std::vector<uint32_t> used;                // records the frame read
};

// Reads the requests table (kRequestSlots * 2 words) and the used stamps of
// `records` records back; `live(r)` whether record r is in use.
void read_vector_feedback(GLuint requests, GLuint used, uint32_t records, uint32_t frame,
                          const std::function<bool(uint32_t)>& live, VectorFeedback& out);

// Where the view origin lies in tiles of zoom `zoom` of the layer tiling `lt`
// (which may cross from the terrain's CRS), and the crossing's uniforms:
// u_ref, u_cross, u_cross_param, u_crs_per_m.
void set_vector_ref(const GlProgram& p, const View& view, const WorldFrame& world,
                    const tileformat::Tiling& lt, CrsCross cross, int zoom);

// The G-buffer's colour, position and ground textures on units 0..3 as
// u_color, u_position, u_ground and u_ground_dy (after UseProgram).
void bind_gbuffer(const GlProgram& p, const GBuffer& g);

// The record table of a frame: the records' words (2 uvec4 each) into
// `records`, the tile -> record hash table (tile_table.hpp) into `table`
// (its mask into table_mask), and the used stamps and requests cleared.
void upload_vector_tables(GLuint records, GLuint table, GLuint used, GLuint requests,
                          const std::vector<glm::uvec4>& words,
                          const std::vector<std::pair<tileformat::TileId, uint32_t>>& entries,
                          uint32_t& table_mask);

// Every uniform of kVectorPixelGlsl but the textures and buffers: the
// reference at the package's finest zoom, its zooms, the zoom bias for
// tiles of `tile_px` pixels, u_tile_m0, the lens (centre from the top-left;
// radius 0: none) and deferred_pass_glsl()'s u_inv_view_proj and u_eye.
void set_vector_pixel_uniforms(const GlProgram& p, const View& view, const WorldFrame& world,
                               const tileformat::Tiling& lt, CrsCross cross, int min_zoom,
                               int max_zoom, float tile_px, const glm::vec3& lens, int height);

}  // namespace globe::viewer
