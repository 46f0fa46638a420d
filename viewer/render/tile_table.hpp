// Tile id -> value lookup for shaders: an open-addressing hash table of
// uvec4 (z + 1, x, y, value), linear probing, built on the CPU each frame.
// kTileTableGlsl is the shader side; both use the same hash.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec4.hpp>

#include "tileformat/tile_id.hpp"

namespace globe::viewer {

inline uint32_t tile_hash(int z, uint32_t x, uint32_t y) {
  return (x * 73856093u) ^ (y * 19349663u) ^ (static_cast<uint32_t>(z) * 83492791u);
}

// A power-of-two table with at most half its slots used.
inline std::vector<glm::uvec4> build_tile_table(
    const std::vector<std::pair<tileformat::TileId, uint32_t>>& entries) {
  size_t n = 64;
  while (n < entries.size() * 2)
    n *= 2;
  std::vector<glm::uvec4> table(n, glm::uvec4(0));
  for (const auto& [id, value] : entries) {
    uint32_t h = tile_hash(id.z, id.x, id.y) & (n - 1);
    while (table[h].x != 0)
      h = (h + 1) & (n - 1);
    table[h] = {static_cast<uint32_t>(id.z) + 1, id.x, id.y, value};
  }
  return table;
}

// GLSL of the same hash (declare once per shader).
inline constexpr const char* kTileHashGlsl = R"(
uint tile_hash(int z, ivec2 t) {
  return (uint(t.x) * 73856093u) ^ (uint(t.y) * 19349663u) ^ (uint(z) * 83492791u);
}
)";

// GLSL: the table as buffer `NAME` at `binding`, its `uniform uint
// NAME_mask`, and `int NAME_lookup(int z, ivec2 t)`: the value, or -1.
inline std::string tile_table_glsl(const std::string& name, int binding) {
  return "layout(std430, binding = " + std::to_string(binding) + ") readonly buffer " + name +
         "_block { uvec4 " + name + "[]; };\nuniform uint " + name + "_mask;\nint " + name +
         "_lookup(int z, ivec2 t) {\n  uint h = tile_hash(z, t) & " + name +
         "_mask;\n  for (int i = 0; i < 64; ++i) {\n    uvec4 e = " + name +
         "[h];\n    if (e.x == 0u) return -1;\n"
         "    if (e.x == uint(z + 1) && e.y == uint(t.x) && e.z == uint(t.y)) return int(e.w);\n"
         "    h = (h + 1u) & " +
         name + "_mask;\n  }\n  return -1;\n}\n";
}

}  // namespace globe::viewer
