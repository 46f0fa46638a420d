// Quantized-mesh-1.0 decoding (CesiumGS/quantized-mesh, README.md; the
// spec has no numbered sections, so errors quote its headings): one terrain
// tile of a CesiumJS tileset as the triangles and quantized vertices it
// holds. The bytes come from the network, so every count is checked against
// what is left before anything is allocated, and every index against the
// vertex count. Used by mesh_grid (which samples the mesh on a block's grid)
// and quantized_mesh_reader; touches nothing but the bytes it is given
// (zlib for gzip-encoded bodies).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace globe::viewer {

// "VertexData": u, v run 0 (west, south) to 32767 (east, north).
inline constexpr int kQuantizedMeshMax = 32767;

// "QuantizedMeshHeader" (88 bytes, little-endian).
struct QuantizedMeshHeader {
  std::array<double, 3> center{};  // ECEF metres
  float min_height = 0, max_height = 0;
  std::array<double, 3> bounding_sphere_center{};
  double bounding_sphere_radius = 0;
  std::array<double, 3> horizon_occlusion_point{};  // ellipsoid-scaled ECEF
};

struct QuantizedMesh {
  QuantizedMeshHeader header;
  // Per vertex, after zig-zag and delta decoding: 0..32767 each.
  std::vector<uint16_t> u, v, height;
  // 3 vertex indices per triangle (high-water mark undone), each < u.size().
  std::vector<uint32_t> triangles;
  // "EdgeIndices": the vertices on each edge of the tile, each < u.size().
  std::vector<uint32_t> west, south, east, north;
  // Extension 1 ("octvertexnormals"): 2 bytes per vertex, as stored; empty
  // when absent.
  std::vector<uint8_t> oct_normals;
  // Extension 2 ("watermask"): 1 byte or 256 x 256 bytes; nullopt when absent.
  std::optional<std::vector<uint8_t>> water_mask;
  // Extension 4 ("metadata"): the JSON text; nullopt when absent.
  std::optional<std::string> metadata_json;

  size_t vertex_count() const { return u.size(); }
  size_t triangle_count() const { return triangles.size() / 3; }
  // Height of vertex k in metres: min + height/32767 * (max - min).
  double height_m(size_t k) const {
    return double(header.min_height) + double(height[k]) / kQuantizedMeshMax *
                                           (double(header.max_height) - double(header.min_height));
  }
};

// Decodes one tile; a body starting with the gzip magic (1f 8b) is inflated
// first (at most 256 MiB out). Extensions of unknown id are skipped.
// Throws tileformat::FormatError naming the part of the tile that is wrong
// (truncated, a count larger than the bytes left, an index out of range,
// coordinates outside 0..32767, heights not finite, trailing bytes in an
// extension list, a broken gzip stream).
QuantizedMesh decode_quantized_mesh(std::span<const uint8_t> bytes);

// `bytes` inflated if it starts with the gzip magic, else as is (copied).
// Throws tileformat::FormatError for a broken or oversized gzip stream.
std::vector<uint8_t> gunzip_if_gzipped(std::span<const uint8_t> bytes,
                                       size_t max_out = size_t{256} << 20);

}  // namespace globe::viewer
