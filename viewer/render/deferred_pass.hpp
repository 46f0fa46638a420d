// What every full-screen pass over the G-buffer shares (the line pass and
// the imagery pass): the full-screen triangle, the surface-plane hit used for
// each pixel's footprint, and the GPU feedback of wanted tiles - an
// open-addressing table of (z, x, y, tag) keys the shader fills with atomics
// and the CPU reads back. `tag` tells apart the sources one pass asks for (the
// imagery pass: its layer; the line pass: 0).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tileformat/tile_id.hpp"

namespace globe::viewer {

inline constexpr uint32_t kRequestSlots = 4096;  // power of two; 2 words each

// Full-screen triangle.
inline constexpr const char* kFullScreenVertex = R"(#version 450 core
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

// GLSL (after tile_hash, tile_table.hpp): declares the requests buffer at
// `requests_binding`, `u_request_mask`, `u_position`, `u_inv_view_proj` and
// `u_eye`, and defines
//   vec3 plane_hit(vec2 pixel, vec3 p, vec3 n, out bool ok): where the ray
//     through `pixel` meets the plane (p, n); ok false when edge-on or behind;
//   void request(int z, ivec2 t, uint tag): asks for tile (z, t) once.
inline std::string deferred_pass_glsl(int requests_binding) {
  return "layout(std430, binding = " + std::to_string(requests_binding) +
         R"() buffer Requests { uint requests[]; };  // 2 per slot
uniform uint u_request_mask;
uniform sampler2D u_position;
uniform mat4 u_inv_view_proj;
uniform vec3 u_eye;

vec3 plane_hit(vec2 pixel, vec3 p, vec3 n, out bool ok) {
  vec4 w = u_inv_view_proj * vec4(pixel / vec2(textureSize(u_position, 0)) * 2.0 - 1.0, 1.0, 1.0);
  vec3 dir = w.xyz / w.w - u_eye;
  float denom = dot(dir, n);
  float t = dot(p - u_eye, n) / denom;
  ok = abs(denom) > 1e-5 * length(dir) && t > 0.0;
  return u_eye + t * dir;
}
void request(int z, ivec2 t, uint tag) {
  if (t.x < 0 || t.y < 0) return;
  uint k0 = ((uint(z) << 24) | uint(t.x)) + 1u, k1 = ((tag << 28) | uint(t.y)) + 1u;
  uint h = (tile_hash(z, t) ^ (tag * 2654435761u)) & u_request_mask;
  for (int i = 0; i < 16; ++i) {
    uint p0 = atomicCompSwap(requests[2u * h], 0u, k0);
    if (p0 == 0u || p0 == k0) {
      uint p1 = atomicCompSwap(requests[2u * h + 1u], 0u, k1);
      if (p1 == 0u || p1 == k1) return;
    }
    h = (h + 1u) & u_request_mask;
  }
}
)";
}

struct TileRequest {
  uint32_t tag = 0;
  tileformat::TileId id;
};

// The requests in a read-back table of kRequestSlots * 2 words.
inline std::vector<TileRequest> decode_tile_requests(const std::vector<uint32_t>& words) {
  std::vector<TileRequest> out;
  for (size_t i = 0; i + 1 < words.size(); i += 2) {
    if (words[i] == 0 || words[i + 1] == 0) continue;
    const uint32_t k0 = words[i] - 1, k1 = words[i + 1] - 1;
    out.push_back({k1 >> 28, {static_cast<int>(k0 >> 24), k0 & 0xFFFFFF, k1 & 0xFFFFFFF}});
  }
  return out;
}

}  // namespace globe::viewer
