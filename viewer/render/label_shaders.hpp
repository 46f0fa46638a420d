// GLSL of the label passes (docs/viewer.md "Labels"):
//  - the probe: one point per ground point a label needs (its anchor, a
//    line label's path), placed on the terrain as charts are (the finest
//    resident block's height, kKeyHeightGlsl) and written to texel i of a
//    float image: pixel x, y from the top-left, distance from the eye, and
//    whether it lies in front of the eye and on the near side of the globe;
//  - the depth samples: one point per screen pixel the CPU asks about, the
//    distance from the eye to the terrain the G-buffer holds there (-1 for
//    sky), so that a label is tested at several of its points;
//  - the glyphs: one instanced quad per glyph, rotated about its pivot,
//    drawn from the signed-distance-field atlas with a halo.
#pragma once

namespace globe::viewer::shaders {

// After kFrameWorldGlsl, tile_hash, the terrain table and kKeyHeightGlsl.
inline constexpr const char* kLabelProbeVertex = R"(
layout(location = 0) in ivec2 a_key;  // absolute key units (the integer part)
layout(location = 1) in vec2 a_frac;  // and the fraction
uniform mat4 u_view_proj;
uniform ivec2 u_origin;
uniform vec3 u_eye;
uniform vec2 u_viewport;
uniform int u_row;   // texels per row of the output
uniform int u_rows;  // and its rows
out vec4 v_result;
// Bilinear between the heights at the four key points around the point: the
// anchor between the finest samples, as the terrain is drawn there.
float height_at(ivec2 key, vec2 f) {
  float h00 = terrain_height(key), h10 = terrain_height(key + ivec2(1, 0));
  float h01 = terrain_height(key + ivec2(0, 1)), h11 = terrain_height(key + ivec2(1, 1));
  return mix(mix(h00, h10, f.x), mix(h01, h11, f.x), f.y);
}

void main() {
  ivec2 rel = a_key - u_origin;
  float h = height_at(a_key, a_frac) * u_scale.z;
  vec3 p = frame_world(rel, a_frac, h);
  vec4 c = u_view_proj * vec4(p, 1.0);
  bool front = c.w > 0.0;
  if (u_globe != 0) {
    vec3 up = normalize(frame_world(rel, a_frac, h + 1000.0) - p);
    front = front && dot(up, u_eye - p) > 0.0;
  }
  vec2 ndc = front ? c.xy / c.w : vec2(0.0);
  v_result = vec4((ndc.x * 0.5 + 0.5) * u_viewport.x, (0.5 - ndc.y * 0.5) * u_viewport.y,
                  length(p - u_eye), front ? 1.0 : 0.0);
  int i = gl_VertexID;
  vec2 texel = vec2(float(i % u_row) + 0.5, float(i / u_row) + 0.5);
  gl_Position = vec4(texel / vec2(float(u_row), float(u_rows)) * 2.0 - 1.0, 0.0, 1.0);
}
)";

inline constexpr const char* kLabelPointFragment = R"(#version 450 core
in vec4 v_result;
layout(location = 0) out vec4 o_result;
void main() { o_result = v_result; }
)";

inline constexpr const char* kLabelDepthVertex = R"(#version 450 core
layout(location = 0) in vec2 a_pixel;  // from the top-left
uniform sampler2D u_position;          // the G-buffer's world points (w = 1 on terrain)
uniform vec3 u_eye;
uniform ivec2 u_size;                  // the G-buffer's
uniform int u_row;
uniform int u_rows;
out vec4 v_result;
void main() {
  ivec2 px = ivec2(floor(a_pixel));
  float d = -1.0;
  if (px.x >= 0 && px.y >= 0 && px.x < u_size.x && px.y < u_size.y) {
    vec4 w = texelFetch(u_position, ivec2(px.x, u_size.y - 1 - px.y), 0);
    if (w.w > 0.5) d = length(w.xyz - u_eye);
  } else {
    d = -2.0;  // off screen: unknown
  }
  v_result = vec4(d, 0.0, 0.0, 1.0);
  int i = gl_VertexID;
  vec2 texel = vec2(float(i % u_row) + 0.5, float(i / u_row) + 0.5);
  gl_Position = vec4(texel / vec2(float(u_row), float(u_rows)) * 2.0 - 1.0, 0.0, 1.0);
}
)";

inline constexpr const char* kGlyphVertex = R"(#version 450 core
layout(location = 0) in vec2 a_corner;  // 0..1
layout(location = 1) in vec4 i_pivot;   // pivot x, y (px from the top-left), angle (radians), scale
layout(location = 2) in vec4 i_rect;    // the quad around the pivot before rotation, px (y down)
layout(location = 3) in vec4 i_atlas;   // texels x0, y0, x1, y1
layout(location = 4) in vec4 i_style;   // alpha, halo px, -, -
uniform vec2 u_viewport;
uniform vec2 u_atlas_size;
out vec2 v_uv;
flat out vec4 v_style;
flat out float v_scale;
void main() {
  vec2 local = mix(i_rect.xy, i_rect.zw, a_corner);
  float c = cos(i_pivot.z), s = sin(i_pivot.z);
  vec2 px = i_pivot.xy + vec2(c * local.x - s * local.y, s * local.x + c * local.y);
  gl_Position = vec4(px.x / u_viewport.x * 2.0 - 1.0, 1.0 - px.y / u_viewport.y * 2.0, 0.0, 1.0);
  v_uv = mix(i_atlas.xy, i_atlas.zw, a_corner) / u_atlas_size;
  v_style = i_style;
  v_scale = i_pivot.w;
}
)";

// MapLibre's SDF convention: the outline at 0.75, 1/8 per texel (radius 8).
inline constexpr const char* kGlyphFragment = R"(#version 450 core
in vec2 v_uv;
flat in vec4 v_style;
flat in float v_scale;
uniform sampler2D u_atlas;
uniform vec3 u_fill;
uniform vec3 u_halo;
layout(location = 0) out vec4 o_color;
void main() {
  float v = texture(u_atlas, v_uv).r;
  float per_px = 1.0 / (8.0 * v_scale);  // SDF units per screen pixel
  float aa = 0.7 * per_px;
  float fill = smoothstep(0.75 - aa, 0.75 + aa, v);
  float halo_edge = 0.75 - v_style.y * per_px;
  float halo = smoothstep(halo_edge - aa, halo_edge + aa, v);
  vec3 rgb = mix(u_halo, u_fill, fill);
  float a = max(fill, halo * 0.9) * v_style.x;
  if (a <= 0.0) discard;
  o_color = vec4(rgb, a);
}
)";

}  // namespace globe::viewer::shaders
