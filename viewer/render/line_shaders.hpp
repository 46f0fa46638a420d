// GLSL of the line pass (docs/viewer.md "Lines"): the deferred shader that
// shades every terrain pixel from its line tile's cluster cell, and the
// draped-geometry baseline it is measured against. Both read the line tiles
// from one arena buffer (layout in data/line_cache.hpp).
#pragma once

namespace globe::viewer::shaders {

// Declarations and helpers shared by both programs.
inline constexpr const char* kLineCommon = R"(#version 450 core
layout(std430, binding = 0) readonly buffer Arena { uint arena[]; };
layout(std430, binding = 3) readonly buffer Styles { vec4 styles[]; };  // 7 per class
uniform int u_class_count;

vec2 seg_a(uint o) { return vec2(uintBitsToFloat(arena[o]), uintBitsToFloat(arena[o + 1u])); }
vec2 seg_b(uint o) { return vec2(uintBitsToFloat(arena[o + 2u]), uintBitsToFloat(arena[o + 3u])); }
)";

// The deferred pass. Per pixel (vector_pixel_glsl.hpp): the surface point and
// its plane from the G-buffer give the Jacobian J (world metres per screen
// pixel) of the map position; the line zoom is the finest whose tiles still
// span globe:tile_px pixels at the pixel's area footprint; the segments of
// the pixel's cell are measured in screen pixels through J^-1 (so widths hold
// on slopes and in perspective) and composited: casings under fills, the
// higher (coverage, class) winning, coverage from a 1-px box filter.
// (Follows deferred_pass_glsl(), deferred_pass.hpp, and kVectorPixelGlsl.)
inline constexpr const char* kLineDeferredFragment = R"(
uniform sampler2D u_color;
uniform sampler2D u_line_ramps;  // a row per class coloured by the ground (LineRamp)
uniform float u_units_to_nominal_px;  // tile_px / extent: dash layout scale
uniform float u_world_per_m;          // world units per metre on the ground (world_frame.hpp)
uniform int u_select_only;
layout(location = 0) out vec4 o_color;
layout(location = 1) out uint o_record;  // record + 1 the pixel reads, 0 = none
layout(location = 2) out uint o_segment;  // segment + 1 of the line drawn on top, 0 = none (picking)

// Coverage of a pixel (1-px box filter across the line) by a band of half
// width h around a line at distance d.
float coverage(float d, float h) {
  return clamp(min(d + h, 0.5) - max(d - h, -0.5), 0.0, 1.0);
}
// Fraction of [pos - q/2, pos + q/2] that falls on the dash pattern's "on" parts.
float dash_coverage(float pos, float q, int cls) {
  vec4 d0 = styles[cls * 7 + 3], d1 = styles[cls * 7 + 4];
  float pat[8] = float[8](d0.x, d0.y, d0.z, d0.w, d1.x, d1.y, d1.z, d1.w);
  int n = int(styles[cls * 7 + 2].w);
  float total = 0.0;
  for (int i = 0; i < n; ++i) total += pat[i];
  float p = mod(pos, total), cov = 0.0, s = 0.0;
  for (int i = 0; i < n; i += 2) {
    for (int w = -1; w <= 1; ++w) {
      float o = float(w) * total;
      cov += max(0.0, min(p + 0.5 * q, s + pat[i] + o) - max(p - 0.5 * q, s + o));
    }
    s += pat[i] + pat[i + 1];
  }
  return clamp(cov / q, 0.0, 1.0);
}

// Coverage of a procedural pattern (docs/viewer.md "Line patterns") at
// pixel offset p from the line (x along it, the line's direction ahead; y
// across it), in pixels, from the nearest motif's centre; hw: the line's half
// width in pixels; ahead: 1 where motif positions grow along the line.
//  1 railway: a thin rail with ties across the width at every motif;
//  2 arrows: a thin line with a chevron pointing along the line;
//  3 zigzag: a thin line swinging across the width, one tooth per motif;
//  4 dots: discs of the line's width.
float pattern_coverage(int kind, vec2 p, float hw, float period_px, float phase) {
  float thin = max(0.5, 0.3 * hw);
  float inside = clamp(hw + 0.5 - abs(p.y), 0.0, 1.0);  // within the width
  if (kind == 1) {
    float tie = coverage(abs(p.x), max(0.6, 0.1 * period_px)) * inside;
    return max(coverage(abs(p.y), thin), tie);
  } else if (kind == 2) {
    // Arms from the apex (half a width ahead of the centre) back at 45 degrees.
    float arm = abs(p.x - (0.5 * hw - abs(p.y))) * 0.70710678;
    return max(coverage(abs(p.y), thin), coverage(arm, thin) * inside);
  } else if (kind == 3) {
    float tri = 1.0 - 4.0 * abs(fract(phase + 0.25) - 0.5);  // -1 .. 1 once per motif
    return coverage(abs(p.y - (hw - thin) * tri), thin);
  }
  return coverage(length(p), hw);
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 base = texelFetch(u_color, px, 0);
  o_color = base;
  o_record = 0u;
  o_segment = 0u;
  VectorPixel v;
  if (!vector_pixel(px, v) || v.rec < 0) return;
  int rec = v.rec, zz = v.zz, z = v.z, wanted = v.wanted;
  vec2 local = v.local;
  mat2 J = v.J, Jinv = v.Jinv, L = v.L;
  used[rec] = u_frame;
  o_record = uint(rec) + 1u;
  uvec4 r0 = records[2 * rec], r1 = records[2 * rec + 1];
  if (r1.z != 0u || u_select_only != 0) return;

  float extent = uintBitsToFloat(r1.x), reach = uintBitsToFloat(r1.y);
  uint grid = r0.w;
  vec2 lu = local * extent;
  ivec2 cell = clamp(ivec2(lu * float(grid) / extent), ivec2(0), ivec2(int(grid) - 1));
  uint ci = uint(cell.y) * grid + uint(cell.x);
  uint begin = arena[r0.x + ci], end = arena[r0.x + ci + 1u];
  float reach_m = reach * min(length(L[0]), length(L[1]));
  // Pixel-unit dashes and patterns are laid out in pixels at the zoom the
  // pixel wants (256 per tile edge), also where a coarser tile is drawn
  // (past the package's finest zoom): 1..2 screen pixels each.
  float units_to_px = u_units_to_nominal_px * exp2(float(wanted - zz));
  // The classes covering the pixel, at most kLayers of the highest ids: per
  // class its best casing and fill coverage and the segment of that fill.
  const int kLayers = 4;
  int lay_cls[kLayers];
  float lay_c[kLayers], lay_f[kLayers];
  uint lay_seg[kLayers];
  int layers = 0;
  for (uint k = begin; k < end; ++k) {
    uint seg = arena[r0.y + k];
    uint o = r0.z + seg * 6u;
    int cls = int(arena[o + 4u]);
    if (cls >= u_class_count) continue;
    vec4 st = styles[cls * 7 + 2];  // half width, casing width, unit is metres, dash count
    if (st.x <= 0.0) continue;
    vec2 A = seg_a(o), B = seg_b(o);
    vec2 aw = L * (A - lu), bw = L * (B - lu);
    vec2 as = Jinv * aw, ab = Jinv * bw - as;
    float len2 = dot(ab, ab);
    float t = len2 > 1e-12 ? clamp(-dot(as, ab) / len2, 0.0, 1.0) : 0.0;
    float d = length(as + t * ab);
    float scale = 1.0;  // pixels per style unit across the line
    if (st.z > 0.5) {
      vec2 dw = bw - aw;
      scale = u_world_per_m *
              (len2 > 1e-12 ? abs(dot(Jinv * normalize(vec2(-dw.y, dw.x)), normalize(vec2(-ab.y, ab.x))))
                            : inversesqrt(abs(determinant(J))));
    }
    float hw = st.x * scale, outer = hw + st.y * scale;
    // Across the line, one pixel spans |J n| metres: keep everything drawn
    // within `reach` of the segment, so the cell that lists it is the one
    // the pixel looks in (tileformat §7.3).
    vec2 n_s = len2 > 1e-12 ? normalize(vec2(-ab.y, ab.x)) : vec2(0.7071068);
    // (A finer tile standing in for a broken one reaches less than a pixel
    // here: its lines are kept a pixel wide, where its cells list them.)
    float limit = max(reach_m / length(J * n_s) - 0.5, zz > z ? 0.5 : 0.0);
    if (outer > limit) {
      hw *= limit / outer;
      outer = limit;
    }
    if (d > outer + 0.5) continue;
    float cov_c = st.y > 0.0 ? coverage(d, outer) : 0.0;
    float cov_f = coverage(d, hw);
    vec4 pat = styles[cls * 7 + 5];  // pattern id, motif spacing in the width's unit
    if (pat.x > 0.5 && len2 > 1e-12) {
      // Position along the line in the width's unit (metres, or pixels as the
      // dashes), and screen pixels per that unit along.
      float seg_units = length(B - A);
      float along = uintBitsToFloat(arena[o + 5u]) + t * seg_units;
      float px_per_unit = sqrt(len2) / seg_units;
      float u_per_tile_unit =
          st.z > 0.5 ? length(bw - aw) / (seg_units * u_world_per_m) : units_to_px;
      float a = along * u_per_tile_unit, px_per_u = px_per_unit / u_per_tile_unit;
      float phase = a / pat.y, c = (phase - floor(phase + 0.5)) * pat.y;
      // The pixel's distance from the segment, signed by its side (left of
      // the line's direction > 0): round past the segment's ends.
      float across = (ab.y * as.x - ab.x * as.y) >= 0.0 ? d : -d;
      cov_f = pattern_coverage(int(pat.x + 0.5), vec2(c * px_per_u, across), hw,
                               pat.y * px_per_u, phase);
    }
    if (st.w > 0.0 && cov_f > 0.0 && len2 > 1e-12) {
      float seg_units = length(B - A);
      float along = uintBitsToFloat(arena[o + 5u]) + t * seg_units;
      float px_per_unit = sqrt(len2) / seg_units;
      if (st.z > 0.5) {
        float m_per_u = length(bw - aw) / (seg_units * u_world_per_m);
        cov_f *= dash_coverage(along * m_per_u, m_per_u / px_per_unit, cls);
      } else {
        cov_f *= dash_coverage(along * units_to_px, units_to_px / px_per_unit, cls);
      }
    }
    if (cov_c <= 0.0 && cov_f <= 0.0) continue;
    int at = -1, lowest = 0;
    for (int i = 0; i < layers; ++i) {
      if (lay_cls[i] == cls) at = i;
      if (lay_cls[i] < lay_cls[lowest]) lowest = i;
    }
    if (at < 0) {
      if (layers < kLayers) {
        at = layers++;
      } else {
        if (cls < lay_cls[lowest]) continue;  // under kLayers higher classes
        at = lowest;
      }
      lay_cls[at] = cls, lay_c[at] = 0.0, lay_f[at] = 0.0, lay_seg[at] = seg;
    }
    lay_c[at] = max(lay_c[at], cov_c);
    if (cov_f > lay_f[at]) lay_f[at] = cov_f, lay_seg[at] = seg;
  }
  // Lowest class first, each casing then fill over what lies under it at its
  // coverage times the class's opacity (styles[cls * 7].a).
  for (int i = 1; i < layers; ++i)
    for (int j = i; j > 0 && lay_cls[j - 1] > lay_cls[j]; --j) {
      int tc = lay_cls[j]; lay_cls[j] = lay_cls[j - 1]; lay_cls[j - 1] = tc;
      float t = lay_c[j]; lay_c[j] = lay_c[j - 1]; lay_c[j - 1] = t;
      t = lay_f[j]; lay_f[j] = lay_f[j - 1]; lay_f[j - 1] = t;
      uint ts = lay_seg[j]; lay_seg[j] = lay_seg[j - 1]; lay_seg[j - 1] = ts;
    }
  vec3 col = base.rgb;
  vec4 under = texelFetch(u_ground_dy, px, 0);  // .z height (m), .w slope (deg) of the ground
  for (int i = 0; i < layers; ++i) {
    int cls = lay_cls[i];
    float a = styles[cls * 7].a;
    vec3 fill = styles[cls * 7].rgb;
    vec4 by = styles[cls * 7 + 6];  // by (1 slope, 2 height), ramp row, value at 0, value at 1
    if (by.x > 0.5) {
      float t = clamp(((by.x < 1.5 ? under.w : under.z) - by.z) / max(by.w - by.z, 1e-6), 0.0, 1.0);
      fill = texture(u_line_ramps, vec2((t * 255.0 + 0.5) / 256.0,
                                        (by.y + 0.5) / float(textureSize(u_line_ramps, 0).y))).rgb;
    }
    col = mix(col, styles[cls * 7 + 1].rgb, lay_c[i] * a);
    col = mix(col, fill, lay_f[i] * a);
    o_segment = lay_seg[i] + 1u;  // the top one stays: what picking names
  }
  o_color = vec4(col, 1.0);
}
)";

// Screen-space quads of the two vertex programs (geometry and lifted):
// 6 vertices per segment (or piece), casing or fill of its class.
inline constexpr const char* kLineQuadGlsl = R"(
uniform vec2 u_viewport;
uniform float u_focal_px;  // pixels per world unit at clip w = 1
uniform float u_world_per_m;
uniform int u_layer;  // 0 casing, 1 fill
flat out vec4 v_color;
const vec4 kCulled = vec4(2.0, 2.0, 2.0, 1.0);  // outside the clip volume

// This vertex's corner of its quad: x 0 at the start, 1 at the end; y the side.
ivec2 quad_corner() {
  const ivec2 corners[6] = ivec2[6](ivec2(0, -1), ivec2(1, -1), ivec2(0, 1), ivec2(0, 1),
                                    ivec2(1, -1), ivec2(1, 1));
  return corners[gl_VertexID];
}
// Class cls's half width in the layer drawn (0: none, or hidden) and its
// colour (into v_color); `metres` whether the width is in metres.
float layer_half_width(int cls, out bool metres) {
  vec4 st = cls < u_class_count ? styles[cls * 7 + 2] : vec4(0);
  v_color = cls < u_class_count ? styles[cls * 7 + (u_layer == 0 ? 1 : 0)] : vec4(0);
  metres = st.z > 0.5;
  return u_layer == 0 ? (st.y > 0.0 ? st.x + st.y : 0.0) : st.x;
}
// Corner cs of the quad of half width hw between clip points ca and cb (both
// in front of the eye), its ends stretched by hw so that quads overlap at
// their joints.
vec4 quad_vertex(vec4 ca, vec4 cb, ivec2 cs, float hw, bool metres) {
  if (metres) hw *= u_world_per_m * u_focal_px / (cs.x == 0 ? ca.w : cb.w);
  vec2 sa = ca.xy / ca.w * u_viewport * 0.5, sb = cb.xy / cb.w * u_viewport * 0.5;
  vec2 dir = length(sb - sa) > 1e-6 ? normalize(sb - sa) : vec2(1, 0);
  vec2 n = vec2(-dir.y, dir.x);
  vec4 c = cs.x == 0 ? ca : cb;
  vec2 off = (n * float(cs.y) + dir * float(cs.x * 2 - 1)) * max(hw, 0.5);  // no AA
  c.xy += off * 2.0 / u_viewport * c.w;
  return c;
}
)";

// The baseline: each segment of a tile as a screen-space quad (6 vertices,
// instanced per segment) at the heights of the finest resident terrain
// block, depth-tested against the terrain with a polygon offset; fragments
// are kept only on pixels that chose this tile in the selection pass (so the
// baseline draws exactly the tiles, and zooms, the deferred pass would).
inline constexpr const char* kLineGeometryVertex = R"(
uniform sampler2DArray u_heights;
uniform TileRef u_terrain_ref;
uniform int u_terrain_min_zoom, u_terrain_max_zoom;
uniform float u_block_steps, u_block_size, u_zscale;
uniform mat4 u_view_proj;
uniform uint u_segs_base;
uniform vec2 u_tile_origin;  // world metres of tile unit (0, 0)
uniform vec2 u_m_per_unit;

float terrain_height(vec2 w) {
  for (int z = u_terrain_max_zoom; z >= u_terrain_min_zoom; --z) {
    vec2 local;
    ivec2 t = tile_at(u_terrain_ref, z, w, local);
    int slot = terrain_table_lookup(z, t);
    if (slot >= 0)
      return texture(u_heights, vec3((local * u_block_steps + 0.5) / u_block_size, float(slot))).r;
  }
  return 0.0;
}
void main() {
  uint o = u_segs_base + uint(gl_InstanceID) * 6u;
  bool metres;
  float hw = layer_half_width(int(arena[o + 4u]), metres);
  if (hw <= 0.0) {
    gl_Position = kCulled;
    return;
  }
  vec2 A = seg_a(o), B = seg_b(o);
  vec2 wa = u_tile_origin + A * u_m_per_unit * vec2(1, -1);
  vec2 wb = u_tile_origin + B * u_m_per_unit * vec2(1, -1);
  vec4 ca = u_view_proj * vec4(wa, terrain_height(wa) * u_zscale, 1.0);
  vec4 cb = u_view_proj * vec4(wb, terrain_height(wb) * u_zscale, 1.0);
  gl_Position = ca.w <= 0.0 || cb.w <= 0.0 ? kCulled : quad_vertex(ca, cb, quad_corner(), hw, metres);
}
)";

inline constexpr const char* kLineGeometryFragment = R"(#version 450 core
flat in vec4 v_color;
uniform usampler2D u_pixel_record;
uniform uint u_record;
out vec4 o_color;
void main() {
  if (texelFetch(u_pixel_record, ivec2(gl_FragCoord.xy), 0).r != u_record + 1u) discard;
  o_color = vec4(v_color.rgb, 1.0);
}
)";

// Lifted lines (--lines lifted, --bundles 3d), in two steps per frame.
// 1. kLineLiftedPoints (compute, one dispatch per tile the selection pass
// chose): each segment is cut into u_pieces pieces and each of its u_pieces + 1
// points lifted above the terrain, into Points: the world position and, in
// w, whether the piece starting there is drawn (pieces that a finer chosen
// tile also covers are left to it). A point's height is the highest of the
// finest resident terrain samples at it and at eight points u_ring_keys
// around it (half the tile's longest piece), plus u_lift, plus the LOD's
// error bound at the point's distance (so no LOD rises above the sampled
// heights); it depends on the point alone, so consecutive segments meet. The
// pieces keep a long segment from sagging into the globe.
// 2. kLineLiftedVertex (one draw per class and layer, over that class's
// segments only, listed in Items): each piece as a screen-space quad
// between its two lifted points, depth-tested against the terrain.
// The compute program follows kLineCommon, the tile hash, the line table,
// the terrain table ("terrain"), kFrameWorldGlsl and kKeyHeightGlsl.
inline constexpr const char* kLineLiftedPoints = R"(
layout(local_size_x = 64) in;
layout(std430, binding = 1) readonly buffer Records { uvec4 records[]; };  // 2 per record
layout(std430, binding = 5) readonly buffer Used { uint used[]; };
layout(std430, binding = 7) writeonly buffer Points { vec4 points[]; };
uniform ivec2 u_origin;  // the view origin, key units
uniform uint u_segs_base, u_frame;
uniform uint u_points_base, u_point_count;  // where this tile's points go, and how many
uniform int u_pieces;
uniform int u_zoom, u_max_zoom;  // the record's zoom, the package's finest
uniform ivec2 u_tile;            // the record's tile
uniform float u_extent;          // its units per edge
uniform vec2 u_tile_key;         // its origin in key units from the view origin
uniform float u_keys_per_unit;
uniform float u_ring_keys;
uniform float u_lift;      // world z units
uniform float u_error_px;  // the terrain LOD's screen-space error bound
uniform float u_focal_px;  // pixels per world unit at clip w = 1
uniform vec3 u_eye;        // world

// World position of tile point P (units), lifted.
vec3 lifted(vec2 P) {
  vec2 k = u_tile_key + P * u_keys_per_unit;
  ivec2 rel = ivec2(floor(k));
  ivec2 key = u_origin + rel;
  int r = max(int(u_ring_keys), 1), d = max(int(u_ring_keys * 0.7071), 1);
  float h = terrain_height(key);
  h = max(h, max(terrain_height(key + ivec2(r, 0)), terrain_height(key - ivec2(r, 0))));
  h = max(h, max(terrain_height(key + ivec2(0, r)), terrain_height(key - ivec2(0, r))));
  h = max(h, max(terrain_height(key + ivec2(d, d)), terrain_height(key - ivec2(d, d))));
  h = max(h, max(terrain_height(key + ivec2(d, -d)), terrain_height(key - ivec2(d, -d))));
  // The drawn LOD surface lies within u_error_px on screen of the samples:
  // within that many pixels' worth of world units at the point's distance.
  vec3 p = frame_world(rel, k - floor(k), h * u_scale.z + u_lift);
  float lod = u_error_px * length(p - u_eye) / u_focal_px;
  return frame_world(rel, k - floor(k), h * u_scale.z + u_lift + lod);
}
// Whether a finer tile chosen this frame covers tile point P.
bool drawn_finer(vec2 P) {
  for (int z = u_zoom + 1; z <= u_max_zoom; ++z) {
    int s = z - u_zoom;
    ivec2 t = (u_tile << s) + ivec2(floor(P / u_extent * float(1 << s)));
    int rec = line_table_lookup(z, t);
    if (rec >= 0 && used[rec] == u_frame && records[2 * rec + 1].z == 0u) return true;
  }
  return false;
}
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_point_count) return;
  uint n = uint(u_pieces) + 1u, seg = i / n, k = i % n;
  uint o = u_segs_base + seg * 6u;
  vec2 A = seg_a(o), B = seg_b(o);
  float t = float(k) / float(u_pieces);
  bool drawn = k < uint(u_pieces) && !drawn_finer(mix(A, B, t + 0.5 / float(u_pieces)));
  points[u_points_base + i] = vec4(lifted(mix(A, B, t)), drawn ? 1.0 : 0.0);
}
)";

// After kLineCommon and kLineQuadGlsl: piece gl_InstanceID % u_pieces of
// item u_item_base + gl_InstanceID / u_pieces (its first point, its class).
inline constexpr const char* kLineLiftedVertex = R"(
layout(std430, binding = 7) readonly buffer Points { vec4 points[]; };
layout(std430, binding = 8) readonly buffer Items { uvec2 items[]; };
uniform mat4 u_view_proj;
uniform uint u_item_base;
uniform int u_pieces;
void main() {
  uvec2 item = items[u_item_base + uint(gl_InstanceID / u_pieces)];
  uint piece = uint(gl_InstanceID % u_pieces);
  bool metres;
  float hw = layer_half_width(int(item.y), metres);
  vec4 pa = points[item.x + piece], pb = points[item.x + piece + 1u];
  if (hw <= 0.0 || pa.w == 0.0) {
    gl_Position = kCulled;
    return;
  }
  vec4 ca = u_view_proj * vec4(pa.xyz, 1.0);
  vec4 cb = u_view_proj * vec4(pb.xyz, 1.0);
  gl_Position = ca.w <= 0.0 || cb.w <= 0.0 ? kCulled : quad_vertex(ca, cb, quad_corner(), hw, metres);
}
)";

inline constexpr const char* kLineLiftedFragment = R"(#version 450 core
flat in vec4 v_color;
out vec4 o_color;
void main() {
  o_color = vec4(v_color.rgb, 1.0);
}
)";

}  // namespace globe::viewer::shaders
