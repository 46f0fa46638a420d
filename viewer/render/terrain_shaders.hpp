// GLSL sources of the terrain pass. The vertex shader is shared by drawing
// and by mesh export (transform feedback), so exported triangles are exactly
// the drawn ones.
#pragma once

namespace globe::viewer::shaders {

// GLSL shared by every pass that places points of the terrain's frame: key
// units relative to the view origin (and a height) -> world position, on
// the flat frame or the WGS84 globe (TerrainRenderer::set_frame_uniforms
// sets the uniforms). On the globe, the key offset from the origin becomes
// latitude/longitude offsets and then the WGS84 point relative to the
// origin's point, in its east-north-up frame, with every large term
// multiplying a small difference (half-angle forms), so float keeps
// millimetres near the eye and the same relative precision far away.
inline constexpr const char* kFrameWorldGlsl = R"(
uniform vec3 u_scale;  // flat: metres per key unit (x, y); world z per metre of height
uniform int u_globe;   // 0 flat, 1 geodetic globe, 2 webmercator globe
uniform vec2 u_rad_per_key;  // globe: longitude radians per key unit; latitude radians
                             // (geodetic) or mercator y / R (webmercator) per key unit
uniform vec4 u_anchor;       // globe: origin latitude, its sine and cosine, mercator y / R
uniform int u_wrap_keys;     // globe: key units per 360 degrees of longitude
const float kA = 6378137.0, kE2 = 0.00669437999014132;

// Full relative precision near 0, where GLSL's built-ins may lose it
// (sinh from a difference of exponentials; the spec bounds sin and atan only
// absolutely): Taylor series below 0.1, good to a few float ulps.
float sinh_precise(float x) {
  if (abs(x) > 0.1) return sinh(x);
  float x2 = x * x;
  return x * (1.0 + x2 * (1.0 / 6.0 + x2 * (1.0 / 120.0 + x2 / 5040.0)));
}
float sin_precise(float x) {
  if (abs(x) > 0.1) return sin(x);
  float x2 = x * x;
  return x * (1.0 - x2 * (1.0 / 6.0 - x2 * (1.0 / 120.0 - x2 / 5040.0)));
}
float atan_precise(float y, float x) {  // x > 0 where it matters
  float t = y / x;
  if (x <= 0.0 || abs(t) > 0.1) return atan(y, x);
  float t2 = t * t;
  return t * (1.0 - t2 * (1.0 / 3.0 - t2 * (1.0 / 5.0 - t2 * (1.0 / 7.0 - t2 / 9.0))));
}

// ENU0 of a vector given in the frame with x at the origin's meridian on the
// equator and z at the north pole, rotated so the origin's longitude is 0.
vec3 to_enu0(vec3 v) {
  return vec3(v.y, -u_anchor.y * v.x + u_anchor.z * v.z, u_anchor.z * v.x + u_anchor.y * v.z);
}

vec3 globe_world(vec2 dk, float h, out vec2 spacing) {
  float lat0 = u_anchor.x, s0 = u_anchor.y, c0 = u_anchor.z;
  float dlon = dk.x * u_rad_per_key.x, dlat;
  if (u_globe == 1) {
    dlat = -dk.y * u_rad_per_key.y;
  } else {  // atan(sinh a) - atan(sinh b) without cancellation, a = b + dy
    float b = u_anchor.w, dy = -dk.y * u_rad_per_key.y, a = b + dy;
    dlat = atan_precise(2.0 * cosh(b + 0.5 * dy) * sinh_precise(0.5 * dy), 1.0 + sinh(a) * sinh(b));
  }
  float lat = lat0 + dlat, s = sin(lat), c = cos(lat);
  float hs = sin_precise(0.5 * dlat);
  float dsin = 2.0 * cos(lat0 + 0.5 * dlat) * hs;   // sin lat - sin lat0
  float dcos = -2.0 * sin(lat0 + 0.5 * dlat) * hs;  // cos lat - cos lat0
  float rw = sqrt(1.0 - kE2 * s * s), rw0 = sqrt(1.0 - kE2 * s0 * s0);
  float n0 = kA / rw0;
  float dn = kA * kE2 * sin(2.0 * lat0 + dlat) * sin_precise(dlat) / (rw * rw0 * (rw + rw0));  // N - N0
  float hl = sin_precise(0.5 * dlon), cl = 1.0 - 2.0 * hl * hl, sl = sin_precise(dlon);
  float dx = (dn * c + h * c + n0 * dcos) * cl - n0 * c0 * 2.0 * hl * hl;
  float dy = (n0 + dn + h) * c * sl;
  float dz = (1.0 - kE2) * (dn * s + n0 * dsin) + h * s;
  float n = n0 + dn;
  // (East-west spacing shrinks to nothing at a geodetic pole; the slope
  // across those slivers is not measurable, so it is bounded.)
  spacing = u_globe == 1 ? vec2(n * max(c, 0.05) * u_rad_per_key.x,
                                n * (1.0 - kE2) / (rw * rw) * u_rad_per_key.y)
                         : vec2(n * c * u_rad_per_key.x);
  return to_enu0(vec3(dx, dy, dz));
}

// World position of the point `frac` (0..1) key units past key point `key`
// (relative to the origin) at height h (world z units: metres times the
// height scale), on either surface.
vec3 frame_world(ivec2 key, vec2 frac, float h) {
  if (u_globe == 0)
    return vec3((float(key.x) + frac.x) * u_scale.x, -(float(key.y) + frac.y) * u_scale.y, h);
  // Longitude offsets into -180..180 degrees in integers, before any
  // rounding: across the antimeridian a neighbour is a small offset.
  ivec2 k = key;
  if (k.x > u_wrap_keys / 2) k.x -= u_wrap_keys;
  if (k.x < -u_wrap_keys / 2) k.x += u_wrap_keys;
  vec2 spacing;
  return globe_world(vec2(k) + frac, h, spacing);
}
)";

// Heights under key points, for passes that place things on the terrain
// (charts, lifted lines); after kFrameWorldGlsl, tile_hash and a terrain
// table named "terrain" of the resident blocks' layers.
inline constexpr const char* kKeyHeightGlsl = R"(
uniform sampler2DArray u_heights;
uniform int u_tmin, u_tmax, u_key_zoom, u_steps;
uniform float u_block_size;

// Metres: the finest resident terrain block's height at the key point
// (bilinear between its samples, longitudes wrapped on the globe), 0 where
// no block is resident.
float terrain_height(ivec2 key) {
  if (u_wrap_keys > 0) key.x = ((key.x % u_wrap_keys) + u_wrap_keys) % u_wrap_keys;
  for (int z = u_tmax; z >= u_tmin; --z) {
    int shift = u_key_zoom - z;
    ivec2 tile = (key >> shift) / u_steps;
    int slot = terrain_lookup(z, tile);
    if (slot < 0) continue;
    vec2 local = vec2(key - ((tile * u_steps) << shift)) / float(1 << shift);
    return texture(u_heights, vec3((local + 0.5) / u_block_size, float(slot))).r;
  }
  return 0.0;
}
)";

// The terrain's vertex shader: kTerrainVertexHead + kFrameWorldGlsl +
// kTerrainVertexMain. Lattice point (i, j) of an instanced patch -> block
// sample -> world metres relative to the frame origin. Integer arithmetic up
// to the last step keeps vertices shared by two blocks bit-identical.
inline constexpr const char* kTerrainVertexHead = R"(#version 450 core
layout(location = 0) in ivec2 a_lattice;
layout(location = 1) in ivec4 i_origin_apex;  // block origin (key units, frame-relative), apex
layout(location = 2) in ivec4 i_uv;           // lattice steps along the two legs (samples)
layout(location = 3) in ivec2 i_layer_shift;  // texture layer, log2(key units per sample)
layout(location = 4) in ivec4 i_neighbours;   // layers of the same zoom's blocks W, E, N, S (-1: none)
uniform mat4 u_view_proj;
uniform vec2 u_ground;  // ground units per key unit (x, y), flat frame at the view latitude
uniform float u_skirt;  // skirt depth as a fraction of the patch's leg (TerrainRenderer::set_skirts)
uniform sampler2DArray u_heights;
out vec3 v_world;
out vec2 v_ground;
out vec2 v_sample;
flat out int v_layer;
flat out ivec4 v_neighbours;
flat out int v_shift;     // log2(key units per sample): the block's zoom is key zoom - shift
flat out vec2 v_spacing;  // metres per block sample (x, y)
flat out ivec2 v_key;     // for mesh capture: key units from the frame origin
out float v_height;       // for mesh capture: metres

)";

inline constexpr const char* kTerrainVertexMain = R"(
void main() {
  // A skirt vertex: a rim vertex again, flagged, lowered below the rim.
  bool skirt = a_lattice.x >= SKIRT_FLAG;
  ivec2 lattice = ivec2(skirt ? a_lattice.x - SKIRT_FLAG : a_lattice.x, a_lattice.y);
  ivec2 local = i_origin_apex.zw + lattice.x * i_uv.xy + lattice.y * i_uv.zw;
  float h = texelFetch(u_heights, ivec3(local, i_layer_shift.x), 0).r;
  if (skirt) {
    float leg_samples = length(vec2(i_uv.xy)) * float(LATTICE);
    h -= u_skirt * leg_samples * u_scale.x * float(1 << i_layer_shift.y);
  }
  ivec2 key = i_origin_apex.xy + (local << i_layer_shift.y);
  vec2 spacing = u_scale.xy;
  if (u_globe == 0) {
    v_world = vec3(float(key.x) * u_scale.x, -float(key.y) * u_scale.y, h * u_scale.z);
    v_ground = v_world.xy;
  } else {
    // Longitude offsets into -180..180 degrees in integers, before any
    // rounding: across the antimeridian a neighbour is a small offset.
    ivec2 k = key;
    if (k.x > u_wrap_keys / 2) k.x -= u_wrap_keys;
    if (k.x < -u_wrap_keys / 2) k.x += u_wrap_keys;
    v_world = globe_world(vec2(k), h * u_scale.z, spacing);
    v_ground = vec2(float(k.x) * u_ground.x, -float(k.y) * u_ground.y);
  }
  v_key = key;
  v_height = h;
  v_sample = vec2(local);
  v_layer = i_layer_shift.x;
  v_neighbours = i_neighbours;
  v_shift = i_layer_shift.y;
  v_spacing = spacing * float(1 << i_layer_shift.y);
  gl_Position = u_view_proj * vec4(v_world, 1.0);
}
)";

// Shading modes: 0 hillshade, 1 elevation ramp, 2 slope, 3 aspect, 4 sky
// view, 5 edges, 6 flow (Shading). With an analysis package, u_layers holds
// per sample the sky-view factor, plan curvature and downhill gradient, and
// u_flow log2 of the upstream area (data/analysis_texels.hpp). Also writes the G-buffer the line
// pass reads: position and surface plane.
inline constexpr const char* kTerrainFragment = R"(#version 450 core
in vec3 v_world;
in vec2 v_ground;
in vec2 v_sample;
flat in int v_layer;
flat in ivec4 v_neighbours;
flat in int v_shift;
flat in vec2 v_spacing;
uniform sampler2DArray u_heights;
uniform sampler2DArray u_mask;
uniform float u_size;      // samples per block side
uniform float u_zscale;    // world z per metre of height (with exaggeration)
uniform float u_exaggeration;
uniform int u_iso_of;  // 0 heights, 1 slope (degrees), 2 upstream area (log2 m^2)
uniform vec3 u_sun;        // unit vector towards the sun
uniform int u_mode;        // MODE_... (render/shading_modes.cpp defines them)
uniform vec3 u_lens;       // a lens: centre (window pixels) and radius (0: none)
uniform int u_lens_mode;   // the mode inside it
uniform int u_lens_shows;  // 0 that mode, 1 isolines every u_lens_iso (2 lines, 3 images: other passes)
uniform float u_lens_iso;
uniform sampler2D u_ramp;  // elevation ramp: RampTable::kEntries x 1 colours
uniform vec2 u_ramp_range; // heights of the ramp's first and last entries (metres)
uniform sampler2DArray u_layers;
uniform int u_has_gradient;  // 1: u_layers holds the analysis package's slope and aspect
uniform int u_ao;          // 1: multiply the sky-view factor onto the colour
uniform float u_edge_scale[32]; // per zoom: plan curvature x spacing where edge colours saturate
uniform float u_slope_top;     // degrees where the slope ramp ends (app/data_ranges.hpp)
uniform float u_sky_low;       // sky-view factor drawn black in the skyview mode
uniform float u_relief[32];     // per zoom: the hillshade's slope stretch (lighting only)
uniform int u_key_zoom;
uniform sampler2DArray u_flow;
uniform vec2 u_flow_range;  // log2 upstream areas: rivers begin to show, darkest
uniform int u_flow_pulses;  // 1: pulses run downstream on the rivers, at u_flow_phase (cycles)
uniform float u_flow_phase;
uniform int u_layer_ramp;   // 1: slope, sky view and flow through the colour ramp (--colormap)
uniform float u_iso_interval;  // isolines every this many metres (0: none)
uniform int u_iso_index;       // every n-th isoline bold (0: none)
uniform vec3 u_iso_rgb;
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_position;  // G-buffer: world point, w = 1 on terrain
layout(location = 2) out vec4 o_normal;    // G-buffer: plane of the drawn triangle
layout(location = 3) out vec4 o_ground;    // G-buffer: ground x, y and their d/dx
layout(location = 4) out vec4 o_ground_dy; // G-buffer: d/dy of ground x, y; height (m), slope (deg)

// The height at block sample s (x east, y south), also just outside the
// block: there from the neighbour of the same zoom (edges are shared, so its
// sample last + d is ours at d), so normals at block edges are central
// differences like everywhere else (no seam). Without that neighbour the
// texture clamps to the edge.
float height_at(vec2 s) {
  float last = u_size - 1.0;
  int layer = v_layer;
  if (s.x < 0.0 && v_neighbours.x >= 0) {
    s.x += last;
    layer = v_neighbours.x;
  } else if (s.x > last && v_neighbours.y >= 0) {
    s.x -= last;
    layer = v_neighbours.y;
  } else if (s.y < 0.0 && v_neighbours.z >= 0) {
    s.y += last;
    layer = v_neighbours.z;
  } else if (s.y > last && v_neighbours.w >= 0) {
    s.y -= last;
    layer = v_neighbours.w;
  }
  return texture(u_heights, vec3((s + 0.5) / u_size, float(layer))).r;
}
vec3 ramp(float h) {  // the entries sit on texel centres
  float n = float(textureSize(u_ramp, 0).x);
  float t = clamp((h - u_ramp_range.x) / max(u_ramp_range.y - u_ramp_range.x, 1e-6), 0.0, 1.0);
  return texture(u_ramp, vec2((t * (n - 1.0) + 0.5) / n, 0.5)).rgb;
}
vec4 layers_at(vec2 s) {
  return texture(u_layers, vec3((s + 0.5) / u_size, float(v_layer)));
}
// Sky-view factor -> brightness: `low` (0.65: a deep valley) black .. 1
// (open) white.
float sky_light(float svf, float low) {
  return clamp((svf - low) / (1.0 - low), 0.0, 1.0);
}
float sky_light(float svf) {
  return sky_light(svf, 0.65);
}
vec3 hue(float h) {
  return clamp(abs(mod(h * 6.0 + vec3(0.0, 4.0, 2.0), 6.0) - 3.0) - 1.0, 0.0, 1.0);
}
void main() {
  if (texture(u_mask, vec3((v_sample + 0.5) / u_size, float(v_layer))).r < 0.5) discard;
  float hx = height_at(v_sample + vec2(1, 0)) - height_at(v_sample - vec2(1, 0));
  float hy = height_at(v_sample + vec2(0, 1)) - height_at(v_sample - vec2(0, 1));
  // Sample y grows southwards, world y northwards.
  vec3 n = normalize(vec3(-hx * u_zscale / (2.0 * v_spacing.x), hy * u_zscale / (2.0 * v_spacing.y), 1.0));
  // The light sees the slopes stretched on coarse grids (render/terrain_renderer.hpp);
  // slope and aspect keep the true normal.
  float relief = u_relief[clamp(u_key_zoom - v_shift, 0, 31)];
  vec3 lit = normalize(vec3(n.xy * relief, n.z));
  float shade = max(dot(lit, u_sun), 0.0);
  bool in_lens = u_lens.z > 0.0 && distance(gl_FragCoord.xy, u_lens.xy) < u_lens.z;
  int mode = in_lens && u_lens_shows == 0 ? u_lens_mode : u_mode;
  float iso_interval = in_lens && u_lens_shows == 1 ? u_lens_iso : u_iso_interval;
  vec3 color;
  if (mode == MODE_HILLSHADE) {
    color = vec3(0.12 + 0.88 * shade);
  } else if (mode == MODE_ELEVATION) {
    float h = height_at(v_sample);
    color = ramp(h) * (0.55 + 0.45 * shade / max(u_sun.z, 0.2));
  } else if (mode == MODE_SLOPE) {
    float slope = u_has_gradient != 0 ? degrees(atan(length(layers_at(v_sample).ba)))
                                    : degrees(acos(clamp(n.z, 0.0, 1.0)));
    color = u_layer_ramp != 0
                ? ramp(slope) * (0.55 + 0.45 * shade / max(u_sun.z, 0.2))
                : mix(vec3(1.0, 1.0, 0.85), vec3(0.75, 0.1, 0.05), clamp(slope / u_slope_top, 0.0, 1.0));
  } else if (mode == MODE_ASPECT) {
    // The downhill direction and steepness: from the analysis package's
    // gradient, else from the drawn triangle's normal.
    vec2 a = u_has_gradient != 0 ? layers_at(v_sample).ba : n.xy;
    float aspect = atan(a.x, a.y) / 6.2831853 + 0.5;
    // With --colormap: the ramp over 0..360 degrees clockwise from north.
    vec3 facing = u_layer_ramp != 0 ? ramp(mod(aspect * 360.0 + 180.0, 360.0)) : hue(aspect);
    color = mix(vec3(0.85), facing, clamp(length(a) * 4.0, 0.0, 1.0));
  } else if (mode == MODE_SKYVIEW) {
    float svf = layers_at(v_sample).r;
    color = u_layer_ramp != 0 ? ramp(svf) : vec3(sky_light(svf, u_sky_low));
  } else if (mode == MODE_FLOW) {
    // Rivers: light blue where they begin, deep blue for the largest.
    vec3 flow = texture(u_flow, vec3((v_sample + 0.5) / u_size, float(v_layer))).rgb;
    float a = flow.r;
    float t = (a - u_flow_range.x) / max(u_flow_range.y - u_flow_range.x, 1e-3);
    color = vec3(0.3 + 0.65 * shade);
    if (u_layer_ramp != 0)
      color = ramp(a) * (0.55 + 0.45 * shade / max(u_sun.z, 0.2));
    else if (t > 0.0)
      color = mix(color, mix(vec3(0.45, 0.75, 1.0), vec3(0.0, 0.15, 0.65), min(t, 1.0)),
                  0.4 + 0.6 * min(t, 1.0));
    if (u_flow_pulses != 0 && t > 0.0) {
      // Crests 8 steps apart along the D8 step downstream (gb), moving
      // downstream as the phase grows; block origins lie a multiple of 8
      // samples apart, so crests meet across block edges of one zoom.
      float along = dot(v_sample, flow.gb) / 8.0 - u_flow_phase;
      float crest = pow(0.5 + 0.5 * cos(6.2831853 * along), 4.0);
      color = mix(color, vec3(0.9, 0.97, 1.0), 0.75 * crest * min(t * 2.0, 1.0));
    }
  } else {  // MODE_EDGES
    // Plan curvature times the sample spacing (the change of grade across
    // the slope per sample), stretched by the data's 95th percentile.
    float scale = u_edge_scale[clamp(u_key_zoom - v_shift, 0, 31)];
    float k = clamp(layers_at(v_sample).g * v_spacing.x / scale, -1.0, 1.0);
    if (u_layer_ramp != 0) {  // --colormap: the ramp over -1 (valleys) .. 1 (ridges)
      color = ramp(k) * (0.55 + 0.45 * shade / max(u_sun.z, 0.2));
    } else {
      color = vec3(0.35 + 0.6 * shade);
      color = mix(color, vec3(0.95, 0.55, 0.2), max(k, 0.0));
      color = mix(color, vec3(0.1, 0.3, 0.75), max(-k, 0.0));
    }
  }
  if (u_ao != 0) color *= 0.3 + 0.7 * sky_light(layers_at(v_sample).r);
  // The ground's own slope (without exaggeration; the package's when it has
  // the gradient), for isolines of slope and the G-buffer.
  float true_slope = u_has_gradient != 0
                         ? degrees(atan(length(layers_at(v_sample).ba)))
                         : degrees(atan(length(n.xy) / max(n.z, 1e-6) / max(u_exaggeration, 1e-6)));
  float iso_field = u_iso_of == 0 ? height_at(v_sample)
                  : u_iso_of == 1 ? true_slope
                                  : texture(u_flow, vec3((v_sample + 0.5) / u_size, float(v_layer))).r;
  if (iso_interval > 0.0 && (u_iso_of != 2 || iso_field > -50.0)) {
    // Isolines of the field (heights by default): the distance to the nearest
    // level in pixels from the level's screen gradient, so a line keeps its
    // width on any slope and at any distance; a 1-px box filter across it.
    float f = iso_field / iso_interval;
    float level = floor(f + 0.5);
    float grad = length(vec2(dFdx(f), dFdy(f)));
    float px = abs(f - level) / max(grad, 1e-6);
    bool bold = u_iso_index > 0 && int(mod(level, float(u_iso_index))) == 0;
    float half_width = bold ? 0.9 : 0.45;
    float cover = clamp(min(px + half_width, 0.5) - max(px - half_width, -0.5), 0.0, 1.0);
    // Where the levels crowd (under a pixel apart) the lines would merge into
    // a smear: they fade out there.
    cover *= clamp(1.0 / max(grad, 1e-6) - 0.75, 0.0, 1.0);
    color = mix(color, u_iso_rgb, cover);
  }
  o_color = vec4(color, 1.0);
  o_position = vec4(v_world, 1.0);
  o_normal = vec4(normalize(cross(dFdx(v_world), dFdy(v_world))), 0.0);
  o_ground = vec4(v_ground, dFdxFine(v_ground));
  // The ground's own height and slope, for the passes that colour by them
  // (lines by slope or height).
  o_ground_dy = vec4(dFdyFine(v_ground), height_at(v_sample), true_slope);
}
)";

}  // namespace globe::viewer::shaders
