// GLSL of the area fill pass (docs/viewer.md "Areas"): per terrain pixel of
// the G-buffer, the polygon its area tile's cell says covers it (the cell's
// winding numbers at its reference point, corrected by the signed crossings of
// the segment from there to the pixel by the cell's edges: data/area_cache.hpp),
// filled in its class's colour over the image so far, and the outlines of the
// polygons whose edges pass within their width (distances in screen pixels
// through the pixel's Jacobian, anti-aliased). Follows kTileRefGlsl, the tile
// hash, the record table, deferred_pass_glsl(), kCrsCrossGlsl and
// kVectorPixelGlsl (vector_pixel_glsl.hpp).
#pragma once

namespace globe::viewer::shaders {

// Declarations before kTileRefGlsl.
inline constexpr const char* kAreaCommon = R"(#version 450 core
layout(std430, binding = 0) readonly buffer Arena { uint arena[]; };
layout(std430, binding = 3) readonly buffer Styles { vec4 styles[]; };  // 2 per class
uniform int u_class_count;
)";

inline constexpr const char* kAreaFillFragment = R"(
uniform sampler2D u_color;
uniform int u_select_only;
uniform vec2 u_area_ref;  // the cells' reference point from their top-left corner (tile units)
layout(location = 0) out vec4 o_color;
layout(location = 1) out uint o_record;   // record + 1 the pixel reads, 0 = none
layout(location = 2) out uint o_polygon;  // polygon + 1 filled on top, 0 = none (picking)

float cross2(vec2 u, vec2 v) { return u.x * v.y - u.y * v.x; }
// The winding number change from the reference point (the origin) to q
// across edge a-b (data/area_cache.cpp, `crossing`, is the same rule).
int crossing(vec2 a, vec2 b, vec2 q) {
  bool sa = cross2(q, a) > 0.0, sb = cross2(q, b) > 0.0;
  if (sa == sb) return 0;
  bool sr = cross2(b - a, -a) > 0.0, sq = cross2(b - a, q - a) > 0.0;
  if (sr == sq) return 0;
  return (sq ? 1 : 0) - (sr ? 1 : 0);
}
float coverage(float d, float h) {
  return clamp(min(d + h, 0.5) - max(d - h, -0.5), 0.0, 1.0);
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 base = texelFetch(u_color, px, 0);
  o_color = base;
  o_record = 0u;
  o_polygon = 0u;
  VectorPixel v;
  if (!vector_pixel(px, v) || v.rec < 0) return;
  used[v.rec] = u_frame;
  o_record = uint(v.rec) + 1u;
  // r0: cell offsets, entries, edge references, grid; r1: extent, edges, flag, polygons.
  uvec4 r0 = records[2 * v.rec], r1 = records[2 * v.rec + 1];
  if (r1.z != 0u || u_select_only != 0) return;
  float extent = uintBitsToFloat(r1.x);
  uint grid = r0.w;
  float cell_units = extent / float(grid);
  vec2 lu = v.local * extent;
  ivec2 cell = clamp(ivec2(lu / cell_units), ivec2(0), ivec2(int(grid) - 1));
  uint ci = uint(cell.y) * grid + uint(cell.x);
  vec2 ref = vec2(cell) * cell_units + u_area_ref;
  vec2 q = lu - ref;
  int top = -1, top_cls = -1;
  float line_cov = 0.0;
  vec3 line_col = vec3(0.0);
  for (uint k = arena[r0.x + ci]; k < arena[r0.x + ci + 1u]; ++k) {
    uint eo = r0.y + k * 4u;
    uint poly = arena[eo];
    int w = int(arena[eo + 1u]);
    uint first = arena[eo + 2u], n = arena[eo + 3u];
    int cls = int(arena[r1.w + poly * 2u]);
    bool styled = cls < u_class_count;
    float half_w = styled ? 0.5 * styles[cls * 2 + 1].w : 0.0;
    float dmin = 1e9;
    for (uint i = 0u; i < n; ++i) {
      uint go = r1.y + arena[r0.z + first + i] * 5u;
      vec2 a = vec2(uintBitsToFloat(arena[go]), uintBitsToFloat(arena[go + 1u])) - ref;
      vec2 b = vec2(uintBitsToFloat(arena[go + 2u]), uintBitsToFloat(arena[go + 3u])) - ref;
      w += crossing(a, b, q);
      if (half_w > 0.0 && arena[go + 4u] == 0u) {  // not where the map's edge cut it
        vec2 as = v.Jinv * (v.L * (a - q)), ab = v.Jinv * (v.L * (b - q)) - as;
        float len2 = dot(ab, ab);
        float t = len2 > 1e-12 ? clamp(-dot(as, ab) / len2, 0.0, 1.0) : 0.0;
        dmin = min(dmin, length(as + t * ab));
      }
    }
    if (w != 0) top = int(poly), top_cls = cls;
    float c = half_w > 0.0 ? coverage(dmin, half_w) : 0.0;
    if (c > line_cov) line_cov = c, line_col = styles[cls * 2 + 1].rgb;
  }
  vec3 col = base.rgb;
  if (top >= 0 && top_cls < u_class_count) col = mix(col, styles[top_cls * 2].rgb, styles[top_cls * 2].a);
  col = mix(col, line_col, line_cov);
  o_polygon = top >= 0 ? uint(top) + 1u : 0u;
  o_color = vec4(col, 1.0);
}
)";

}  // namespace globe::viewer::shaders
