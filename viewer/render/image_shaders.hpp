// GLSL of the imagery pass (docs/viewer.md "Imagery"): one full-screen pass
// after the terrain pass that drapes every image layer over the G-buffer.
// Per pixel and layer: the terrain point's offset from the view origin in the
// terrain's tiling CRS is carried into the image's tiling CRS (the same CRS;
// geodetic <-> webmercator in closed form, stable for small offsets; anything
// else through a grid computed with PROJ), the image zoom follows the pixel's
// footprint in image pixels, the tile comes from the layer's table (or its
// nearest resident ancestor while it loads), and its premultiplied texel,
// filtered across mip levels with the footprint's gradients, is composited
// over the layers below, lit by the terrain's hillshade unless unlit.
#pragma once

namespace globe::viewer::shaders {

inline constexpr int kMaxImageLayers = 8;

// (Follows "#version 450 core", tile_hash, deferred_pass_glsl() and kCrsCrossGlsl.)
inline constexpr const char* kImageFragment = R"(
#define MAX_LAYERS 8
layout(std430, binding = 0) readonly buffer Tables { uvec4 tables[]; };
layout(std430, binding = 2) buffer Used { uint used[]; };
uniform uint u_frame;
uniform sampler2D u_color, u_ground, u_ground_dy;
uniform vec2 u_crs_per_m;   // terrain CRS units per ground unit (x, y)
uniform int u_lit;          // 1: imagery x hillshade; 0: unlit
uniform float u_light_norm; // hillshade value of flat ground
uniform int u_layers;
uniform vec3 u_lens_only;  // images only inside this circle (window pixels; radius 0: everywhere)
uniform int u_mode[MAX_LAYERS];  // 0 same CRS, 1 geodetic -> webmercator, 2 webmercator -> geodetic, 3 grid
uniform ivec2 u_base[MAX_LAYERS];
uniform vec2 u_frac[MAX_LAYERS];
uniform vec2 u_per_unit[MAX_LAYERS];  // tiles of the reference zoom per image CRS unit
uniform int u_ref_zoom[MAX_LAYERS], u_min_zoom[MAX_LAYERS], u_max_zoom[MAX_LAYERS];
uniform int u_wrap[MAX_LAYERS];  // tiles across 360 degrees at zoom 0; 0: no wrap
uniform float u_tile_px[MAX_LAYERS], u_opacity[MAX_LAYERS];
uniform vec2 u_param[MAX_LAYERS];     // mode 1: (lat0 rad, R); mode 2: (y0 / R, R)
uniform vec2 u_grid_org[MAX_LAYERS];  // the view origin in grid cells (x east, y south)
uniform vec2 u_grid_inv_cell[MAX_LAYERS];
uniform int u_grid_n;
uniform uint u_table_offset[MAX_LAYERS], u_table_mask[MAX_LAYERS], u_slot_offset[MAX_LAYERS];
uniform sampler2DArray u_images[MAX_LAYERS];
uniform sampler2DArray u_grids;
layout(location = 0) out vec4 o_color;

// The layer's table value for tile (z, t), or -1 (unknown: not asked yet).
int table_lookup(int L, int z, ivec2 t) {
  uint mask = u_table_mask[L], off = u_table_offset[L];
  uint h = tile_hash(z, t) & mask;
  for (int i = 0; i < 64; ++i) {
    uvec4 e = tables[off + h];
    if (e.x == 0u) return -1;
    if (e.x == uint(z + 1) && e.y == uint(t.x) && e.z == uint(t.y)) return int(e.w);
    h = (h + 1u) & mask;
  }
  return -1;
}
// The tile of zoom z holding reference-zoom tile g, in its own column past
// the antimeridian too.
ivec2 tile_column(int L, int z, ivec2 g) {
  ivec2 t = g >> (u_ref_zoom[L] - z);
  if (u_wrap[L] > 0) {
    int n = u_wrap[L] << z;
    t.x = ((t.x % n) + n) % n;
  }
  return t;
}
int tile_at(int L, int z, ivec2 g) {
  return table_lookup(L, z, tile_column(L, z, g));
}
// Grid value (image CRS relative to the grid's anchor) at grid position g;
// false outside the grid.
bool grid_at(int L, vec2 g, out vec2 v) {
  float hi = float(u_grid_n - 1);
  if (!(g.x >= 0.0 && g.y >= 0.0 && g.x <= hi && g.y <= hi)) return false;
  ivec2 i = min(ivec2(floor(g)), ivec2(u_grid_n - 2));
  vec2 f = g - vec2(i);
  vec2 a = texelFetch(u_grids, ivec3(i, L), 0).xy, b = texelFetch(u_grids, ivec3(i + ivec2(1, 0), L), 0).xy;
  vec2 c = texelFetch(u_grids, ivec3(i + ivec2(0, 1), L), 0).xy, d = texelFetch(u_grids, ivec3(i + 1, L), 0).xy;
  v = mix(mix(a, b, f.x), mix(c, d, f.x), f.y);
  return true;
}
// Image CRS offset (x east, y north) from the layer's anchor of the terrain
// CRS offset d from the view origin; false where the image CRS is undefined.
bool image_offset(int L, vec2 d, out vec2 c) {
  int mode = u_mode[L];
  if (mode == 0) {
    c = d;
  } else if (mode <= 2) {
    cross_offset(mode, u_param[L], d, c);  // imagery clamps to the edge row
  } else {
    return grid_at(L, u_grid_org[L] + vec2(d.x, -d.y) * u_grid_inv_cell[L], c);
  }
  return true;
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 base = texelFetch(u_color, px, 0);
  o_color = base;
  vec4 p4 = texelFetch(u_position, px, 0);
  if (p4.w == 0.0) return;
  if (u_lens_only.z > 0.0 && distance(gl_FragCoord.xy, u_lens_only.xy) >= u_lens_only.z) return;
  // The pixel's ground point and its neighbours' (terrain_renderer.hpp):
  // the terrain CRS offset from the view origin and the pixel's footprint.
  vec4 gr = texelFetch(u_ground, px, 0);
  vec2 gdy = texelFetch(u_ground_dy, px, 0).xy;
  float light = u_lit != 0 ? clamp(base.g / u_light_norm, 0.0, 1.25) : 1.0;
  vec2 d0 = gr.xy * u_crs_per_m, d1 = (gr.xy + gr.zw) * u_crs_per_m, d2 = (gr.xy + gdy) * u_crs_per_m;
  vec3 rgb = base.rgb;
  for (int L = 0; L < u_layers; ++L) {
    vec2 c0, c1, c2;
    if (!image_offset(L, d0, c0)) continue;
    if (!image_offset(L, d1, c1)) c1 = c0;
    if (!image_offset(L, d2, c2)) c2 = c0;
    vec2 flip = vec2(1, -1) * u_per_unit[L];
    vec2 p = u_frac[L] + c0 * flip;  // reference-zoom tiles from the base tile
    mat2 Jt = mat2((c1 - c0) * flip, (c2 - c0) * flip);  // ref tiles per screen pixel
    float fp = sqrt(abs(determinant(Jt))) * u_tile_px[L];  // ref-zoom image pixels per screen pixel
    int ref = u_ref_zoom[L];
    int z = fp > 0.0 ? int(ceil(float(ref) - log2(fp))) : ref;
    z = clamp(z, u_min_zoom[L], u_max_zoom[L]);
    vec2 fl = floor(p);
    ivec2 g = u_base[L] + ivec2(fl);
    int v = -1, zz = z;
    bool ask = true;  // request the wanted tile, or the first unknown one past a broken tile
    bool finer = true;  // below the first broken tile, its children are tried once
    for (; zz >= u_min_zoom[L]; --zz) {
      int e = tile_at(L, zz, g);
      if (e == -1) {
        if (ask) request(zz, tile_column(L, zz, g), uint(L));
        ask = false;
        continue;
      }
      if (e == int(0xFFFFFFFDu)) {  // broken: the finer tiles under it, then the coarser
        ask = true;
        if (finer) {
          finer = false;
          for (int zf = zz + 1; zf <= min(zz + 2, u_max_zoom[L]) && v < 0; ++zf) {
            int ef = tile_at(L, zf, g);
            if (ef == -1) request(zf, tile_column(L, zf, g), uint(L));
            if (ef == -1 || ef == int(0xFFFFFFFEu)) break;
            if (ef != int(0xFFFFFFFDu)) v = ef, zz = zf;
          }
          if (v >= 0) break;
        }
        continue;
      }
      if (e == int(0xFFFFFFFEu)) break;     // absent: the layers below show
      v = e;
      break;
    }
    if (v < 0) continue;
    int s = ref - zz;
    vec2 local = (vec2(g - ((g >> s) << s)) + (p - fl)) / float(1 << s);
    used[u_slot_offset[L] + uint(v)] = u_frame;
    float scale = exp2(float(zz - ref));
    vec4 img = textureGrad(u_images[L], vec3(local, float(v)), Jt[0] * scale, Jt[1] * scale);
    float a = img.a * u_opacity[L];
    rgb = rgb * (1.0 - a) + img.rgb * u_opacity[L] * light;
  }
  o_color = vec4(rgb, 1.0);
}
)";

}  // namespace globe::viewer::shaders
