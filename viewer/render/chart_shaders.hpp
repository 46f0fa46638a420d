// GLSL of the chart pass (docs/viewer.md "Charts"). Each place is one
// instance: its key point (absolute key units), its chart parameters and up
// to 16 values. The vertex shader finds the terrain height under the place in
// the finest resident block (the terrain table), places the anchor with the
// terrain's own frame code (kFrameWorldGlsl, flat or globe), and culls it
// behind the globe's horizon.
//  - sprites (pie, bar, stacked): a screen-aligned quad around the anchor,
//    its depth taken a chart radius towards the eye (so the ground right in
//    front of the place does not cut the chart), and the fragment shader
//    draws the slices or bars with antialiased edges and an outline;
//  - columns: boxes standing on the terrain along the place's up vector,
//    one per value, lit by the sun.
// Both write the instance's pick id (index + 1) to a second attachment.
#pragma once

#include <string>

namespace globe::viewer::shaders {

// Declarations and helpers both vertex shaders share (after
// kFrameWorldGlsl, tile_hash, the terrain table and kKeyHeightGlsl).
inline constexpr const char* kChartCommonVertex = R"(
layout(location = 1) in ivec2 i_key;     // absolute key units (the integer part)
layout(location = 9) in vec2 i_frac;     // and the fraction
layout(location = 2) in vec4 i_params;   // per kind, see ChartInstance
layout(location = 3) in vec4 i_v0;
layout(location = 4) in vec4 i_v1;
layout(location = 5) in vec4 i_v2;
layout(location = 6) in vec4 i_v3;
layout(location = 7) in uint i_pick;
uniform mat4 u_view_proj;
uniform ivec2 u_origin;  // the view origin, key units
uniform vec3 u_eye;      // world
uniform int u_fields;

float value(int i) {
  vec4 v = i < 4 ? i_v0 : i < 8 ? i_v1 : i < 12 ? i_v2 : i_v3;
  return v[i & 3];
}

// The anchor in the world and its up vector; false behind the horizon.
bool anchor(out vec3 p, out vec3 up) {
  ivec2 rel = i_key - u_origin;
  float h = terrain_height(i_key) * u_scale.z;
  p = frame_world(rel, i_frac, h);
  up = u_globe == 0 ? vec3(0, 0, 1) : normalize(frame_world(rel, i_frac, h + 1000.0) - p);
  return u_globe == 0 || dot(up, u_eye - p) > 0.0;
}
)";

inline constexpr const char* kChartSpriteMain = R"(
layout(location = 0) in vec2 a_corner;  // 0..1
uniform vec2 u_viewport;
uniform float u_focal_px;  // pixels per world unit at clip w = 1
uniform int u_kind;        // 0 pie, 1 bar, 2 stacked
out vec2 v_px;             // pixels from the anchor, y up
flat out vec4 v_params;
flat out vec4 v_a, v_b, v_c, v_d;
flat out uint v_pick;
void main() {
  v_params = i_params;
  v_a = i_v0, v_b = i_v1, v_c = i_v2, v_d = i_v3;
  v_pick = i_pick;
  vec3 p, up;
  vec4 c = vec4(0);
  if (anchor(p, up)) c = u_view_proj * vec4(p, 1.0);
  if (c.w <= 0.0) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // culled
    return;
  }
  // The chart's rectangle in pixels around the anchor (1 px of margin).
  vec4 r;
  if (u_kind == 0) {
    float rad = 0.5 * i_params.x;
    r = vec4(-rad, -rad, rad, rad);
  } else if (u_kind == 1) {
    float w = float(u_fields) * (i_params.z + 1.0) - 1.0, lo = 0.0, hi = 0.0;
    for (int i = 0; i < u_fields; ++i) {
      lo = min(lo, value(i) * i_params.y);
      hi = max(hi, value(i) * i_params.y);
    }
    r = vec4(-0.5 * w, lo, 0.5 * w, hi);
  } else {
    float total = 0.0;
    for (int i = 0; i < u_fields; ++i) total += max(value(i), 0.0);
    r = vec4(-0.5 * i_params.z, 0.0, 0.5 * i_params.z, total * i_params.y);
  }
  r += vec4(-1.5, -1.5, 1.5, 1.5);
  v_px = mix(r.xy, r.zw, a_corner);
  // Depth a chart radius towards the eye.
  float radius = max(max(-r.x, r.z), max(-r.y, r.w));
  vec3 towards = normalize(u_eye - p) * radius * c.w / u_focal_px;
  vec4 b = u_view_proj * vec4(p + towards, 1.0);
  gl_Position = vec4(c.xy / c.w + v_px * 2.0 / u_viewport, b.w > 0.0 ? b.z / b.w : -1.0, 1.0);
}
)";

inline constexpr const char* kChartSpriteFragment = R"(#version 450 core
in vec2 v_px;
flat in vec4 v_params;
flat in vec4 v_a, v_b, v_c, v_d;
flat in uint v_pick;
uniform int u_kind, u_fields;
uniform vec4 u_colors[16];
uniform vec4 u_outline;       // rgb, width in px (0: none)
uniform float u_opacity;
layout(location = 0) out vec4 o_color;
layout(location = 1) out uint o_pick;
const float kTau = 6.28318530718;

float value(int i) {
  vec4 v = i < 4 ? v_a : i < 8 ? v_b : i < 12 ? v_c : v_d;
  return v[i & 3];
}

// Coverage of a pixel centred `d` px inside an edge (negative: outside).
float cover(float d) { return clamp(d + 0.5, 0.0, 1.0); }

void emit(vec3 rgb, float alpha) {
  if (alpha <= 0.0) discard;
  o_color = vec4(rgb, alpha * u_opacity);
  o_pick = v_pick;
}

void pie() {
  float rad = 0.5 * v_params.x, d = length(v_px);
  float total = 0.0;
  int slices = 0;
  for (int i = 0; i < u_fields; ++i) {
    total += max(value(i), 0.0);
    slices += value(i) > 0.0 ? 1 : 0;
  }
  if (total <= 0.0) discard;
  // Clockwise from the top, as pies are read.
  float a = atan(v_px.x, v_px.y);
  if (a < 0.0) a += kTau;
  float start = 0.0, sep = 1e9;
  int slice = u_fields - 1;
  for (int i = 0; i < u_fields; ++i) {
    float v = max(value(i), 0.0);
    if (v <= 0.0) continue;
    float end = start + v / total * kTau;
    // Distance in pixels to this slice's first edge (a ray from the centre).
    if (slices > 1) {
      float da = a - start;
      if (cos(da) > 0.0) sep = min(sep, d * abs(sin(da)));
    }
    if (a >= start && a < end) slice = i;
    start = end;
  }
  vec3 rgb = u_colors[slice].rgb;
  if (u_outline.w > 0.0) {
    float line = max(cover(u_outline.w * 0.5 - sep), cover(d - (rad - u_outline.w)));
    rgb = mix(rgb, u_outline.rgb, line);
  }
  emit(rgb, cover(rad - d));
}

// A bar from y0 to y1 (either order) over x0..x1: its colour and coverage.
bool bar(float x0, float x1, float y0, float y1, vec3 fill, out vec4 out_rgba) {
  float lo = min(y0, y1), hi = max(y0, y1);
  float inside = min(min(v_px.x - x0, x1 - v_px.x), min(v_px.y - lo, hi - v_px.y));
  if (inside < -0.5) return false;
  vec3 rgb = fill;
  if (u_outline.w > 0.0) rgb = mix(rgb, u_outline.rgb, cover(u_outline.w - inside));
  out_rgba = vec4(rgb, cover(inside));
  return true;
}

void bars() {
  float bw = v_params.z, w = float(u_fields) * (bw + 1.0) - 1.0;
  int i = int(floor((v_px.x + 0.5 * w) / (bw + 1.0)));
  if (i < 0 || i >= u_fields) discard;
  float x0 = -0.5 * w + float(i) * (bw + 1.0);
  vec4 c;
  if (!bar(x0, x0 + bw, 0.0, value(i) * v_params.y, u_colors[i].rgb, c)) discard;
  emit(c.rgb, c.a);
}

void stacked() {
  float y = 0.0;
  for (int i = 0; i < u_fields; ++i) {
    float h = max(value(i), 0.0) * v_params.y;
    if (h <= 0.0) continue;
    vec4 c;
    if (v_px.y < y + h + 0.5 && bar(-0.5 * v_params.z, 0.5 * v_params.z, y, y + h,
                                    u_colors[i].rgb, c)) {
      emit(c.rgb, c.a);
      return;
    }
    y += h;
  }
  discard;
}

void main() {
  if (u_kind == 0) pie();
  else if (u_kind == 1) bars();
  else stacked();
}
)";

inline constexpr const char* kChartColumnMain = R"(
layout(location = 0) in vec3 a_box;     // unit box: x, y in -0.5..0.5, z in 0..1
layout(location = 8) in vec3 a_normal;  // box-local
uniform float u_column_gap;
out vec3 v_normal;
flat out int v_field;
flat out uint v_pick;
void main() {
  // Instances come u_fields per place (the place's attributes advance every
  // u_fields instances): one column per value.
  int k = gl_InstanceID % u_fields;
  v_field = k;
  v_pick = i_pick;
  vec3 p, up;
  if (!anchor(p, up) || value(k) == 0.0) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    return;
  }
  ivec2 rel = i_key - u_origin;
  vec3 east = u_globe == 0 ? vec3(1, 0, 0)
                           : normalize(frame_world(rel + ivec2(256, 0), i_frac, 0.0) -
                                       frame_world(rel, i_frac, 0.0));
  east = normalize(east - dot(east, up) * up);
  vec3 north = cross(up, east);
  float foot = i_params.x, height = value(k) * i_params.y;
  float offset = (float(k) - 0.5 * float(u_fields - 1)) * foot * (1.0 + u_column_gap);
  vec3 q = p + east * (offset + a_box.x * foot) + north * (a_box.y * foot) + up * (a_box.z * height);
  v_normal = east * a_normal.x + north * a_normal.y + up * a_normal.z * sign(height);
  gl_Position = u_view_proj * vec4(q, 1.0);
}
)";

inline constexpr const char* kChartColumnFragment = R"(#version 450 core
in vec3 v_normal;
flat in int v_field;
flat in uint v_pick;
uniform vec4 u_colors[16];
uniform vec3 u_sun;
layout(location = 0) out vec4 o_color;
layout(location = 1) out uint o_pick;
void main() {
  float light = 0.45 + 0.55 * max(dot(normalize(v_normal), u_sun), 0.0);
  o_color = vec4(u_colors[v_field].rgb * light, 1.0);
  o_pick = v_pick;
}
)";

}  // namespace globe::viewer::shaders
