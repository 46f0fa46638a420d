// GLSL of the heatmap pass (docs/viewer.md "Heatmaps"): a kernel density of
// the places, per pixel over the terrain.
//  1. splat: one quad per place around its anchor (kChartCommonVertex: the
//     terrain height under it, the terrain's frame), large enough for the
//     kernel's ground radius (plus the relief's reach on screen); each
//     fragment reads its own ground point from the G-buffer and adds the
//     place's weight times the kernel at that ground distance (a quartic
//     kernel integrating to 1 over the ground: the total is honest) into
//     a float image, blended additively;
//  2. colour: a full-screen pass lays the density over the frame through a
//     yellow-orange-red ramp, transparent where there is none.
#pragma once

namespace globe::viewer::shaders {

// ChartInstance params: ground x, y (the G-buffer's ground frame, relative
// to the view origin), weight, kernel radius (ground units).
inline constexpr const char* kHeatSplatMain = R"(
layout(location = 0) in vec2 a_corner;  // 0..1
uniform vec2 u_viewport;
uniform float u_focal_px;  // pixels per world unit at clip w = 1
uniform float u_margin;    // world units added to the radius: the relief's reach
flat out vec4 v_heat;
void main() {
  v_heat = i_params;
  vec4 c = u_view_proj * vec4(frame_world(i_key - u_origin, i_frac,
                                          terrain_height(i_key) * u_scale.z), 1.0);
  float reach = i_params.w + u_margin;
  vec2 corner = a_corner * 2.0 - 1.0;
  if (c.w <= reach) {  // the eye inside the reach: the whole screen
    gl_Position = vec4(corner, 0.0, 1.0);
    return;
  }
  float rad_px = reach * u_focal_px / (c.w - reach) + 2.0;
  gl_Position = vec4(c.xy / c.w + corner * rad_px * 2.0 / u_viewport, 0.0, 1.0);
}
)";

inline constexpr const char* kHeatSplatFragment = R"(#version 450 core
flat in vec4 v_heat;
uniform sampler2D u_gbuffer_ground, u_gbuffer_position;  // (u_ground is the frame's)
layout(location = 0) out float o_density;
void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  if (texelFetch(u_gbuffer_position, px, 0).w == 0.0) discard;
  vec2 d = texelFetch(u_gbuffer_ground, px, 0).xy - v_heat.xy;
  float r2 = v_heat.w * v_heat.w, q = dot(d, d) / r2;
  if (q >= 1.0) discard;
  // Quartic (biweight) kernel: 3 / (pi r^2) (1 - d^2/r^2)^2, integral 1.
  o_density = v_heat.z * 0.95492966 / r2 * (1.0 - q) * (1.0 - q);
}
)";

inline constexpr const char* kHeatColorFragment = R"(#version 450 core
uniform sampler2D u_density, u_heat_ramp;
uniform float u_top, u_opacity;
uniform int u_has_ramp;  // 1: u_heat_ramp (a colour file) instead of the built-in ramp
layout(location = 0) out vec4 o_color;  // blended over the frame
void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  float t = clamp(texelFetch(u_density, px, 0).r / max(u_top, 1e-30), 0.0, 1.0);
  // ColorBrewer YlOrRd, light to dark.
  const vec3 stops[5] = vec3[5](vec3(1.0, 1.0, 0.698), vec3(0.996, 0.8, 0.361),
                                vec3(0.992, 0.553, 0.235), vec3(0.941, 0.231, 0.125),
                                vec3(0.741, 0.0, 0.149));
  float s = t * 4.0;
  int i = min(int(s), 3);
  vec3 heat = mix(stops[i], stops[i + 1], s - float(i));
  float alpha = u_opacity * clamp(t * 8.0, 0.0, 1.0);
  if (u_has_ramp != 0) {  // its own colours and alphas
    vec4 c = texture(u_heat_ramp, vec2((t * 255.0 + 0.5) / 256.0, 0.5));
    heat = c.rgb;
    alpha = u_opacity * c.a * (t > 0.0 ? 1.0 : 0.0);
  }
  o_color = vec4(heat, alpha);
}
)";

}  // namespace globe::viewer::shaders
