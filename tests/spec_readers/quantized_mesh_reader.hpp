// Independent quantized-mesh-1.0 decoder, written only from the public
// specification (CesiumGS/quantized-mesh, README.md). The tests use it to check
// terrain tiles that the project writes; it shares no code with the project.
//
// The README has no numbered sections; comments quote its headings:
//   "QuantizedMeshHeader"  88 bytes: center, min/max height, bounding sphere,
//                          horizon occlusion point (all little-endian).
//   "VertexData"           vertexCount, then u[], v[], height[] as zig-zag
//                          encoded deltas (uint16).
//   "IndexData16/32"       32-bit when vertexCount > 65536 (64 * 1024); padding
//                          before it to 2- / 4-byte alignment; indices use
//                          high-water-mark encoding.
//   "EdgeIndices16/32"     west, south, east, north vertex lists (not encoded).
//   "Extensions"           {uint8 id, uint32 length, data}: 1 = oct-encoded
//                          vertex normals, 2 = water mask, 4 = metadata JSON.
// "Terrain tiles are served gzipped": input starting with 1f 8b is inflated.
//
// Bytes are passed as std::string_view. Every problem is reported as
// std::runtime_error("quantized-mesh: ...") naming what is wrong and where.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "spec_readers/gunzip.hpp"

namespace spec_readers::quantized_mesh {

constexpr int kQuantizedMax = 32767;  // "VertexData": 0 = west/south/min, 32767 = east/north/max
constexpr std::uint32_t kMax16BitVertices = 65536;  // "more than 65536 vertices" -> 32-bit indices
constexpr std::size_t kHeaderSize = 88;             // 3*8 + 2*4 + 4*8 + 3*8
constexpr std::size_t kWaterMaskGridSize = 256;

// "QuantizedMeshHeader".
struct Header {
  std::array<double, 3> center{};  // tile center, Earth-centered fixed (ECEF) metres
  float min_height = 0;            // metres
  float max_height = 0;
  std::array<double, 3> bounding_sphere_center{};   // ECEF
  double bounding_sphere_radius = 0;                // metres
  std::array<double, 3> horizon_occlusion_point{};  // ellipsoid-scaled ECEF
};

// One extension as stored ("ExtensionHeader" + data).
struct Extension {
  std::uint8_t id = 0;
  std::string data;
};

struct Mesh {
  Header header;
  // "VertexData" after zig-zag + delta decoding: quantized values 0..32767.
  std::vector<std::uint16_t> u, v, height;
  // "IndexData": decoded (high-water-mark undone) indices, 3 per triangle,
  // counter-clockwise.
  std::vector<std::uint32_t> triangles;
  bool indices_are_32bit = false;
  std::size_t index_padding_bytes = 0;  // padding found before the IndexData
  // "EdgeIndices": vertex indices on each tile edge.
  std::vector<std::uint32_t> west_indices, south_indices, east_indices, north_indices;
  // Every extension in file order, raw.
  std::vector<Extension> extensions;
  // Extension 1: the raw oct bytes (x, y per vertex) and the decoded unit vectors.
  std::vector<std::uint8_t> oct_normals;
  std::vector<std::array<double, 3>> normals;
  // Extension 2: 1 byte (all land 0 / all water 255) or 256 x 256 bytes, rows
  // north to south, columns west to east.
  std::optional<std::vector<std::uint8_t>> water_mask;
  // Extension 4: the JSON text.
  std::optional<std::string> metadata_json;

  std::size_t vertex_count() const { return u.size(); }
  std::size_t triangle_count() const { return triangles.size() / 3; }
  bool has_normals() const { return !normals.empty() || has_extension(1); }
  bool has_extension(std::uint8_t id) const {
    for (const Extension& e : extensions) {
      if (e.id == id) return true;
    }
    return false;
  }
};

namespace detail {

[[noreturn]] inline void fail(const std::string& what) {
  throw std::runtime_error("quantized-mesh: " + what);
}

// gzip (RFC 1952): one gzip member, nothing after it (spec_readers/gunzip.hpp).
inline std::string gunzip(std::string_view in, std::size_t max_output = std::size_t{1} << 30) {
  return spec_readers::gunzip(in, "quantized-mesh: ", max_output);
}

// Little-endian cursor over the (decompressed) tile with bounds checks.
struct Cursor {
  std::string_view bytes;
  std::size_t pos = 0;

  void need(std::size_t count, const std::string& what) const {
    if (count > bytes.size() - pos) {
      fail("truncated " + what + ": needs " + std::to_string(count) + " bytes at byte " +
           std::to_string(pos) + " but the tile has " + std::to_string(bytes.size()) + " bytes");
    }
  }
  std::uint64_t uint(int width, const std::string& what) {
    need(width, what);
    std::uint64_t value = 0;
    for (int i = width - 1; i >= 0; --i) {
      value = (value << 8) | static_cast<unsigned char>(bytes[pos + i]);
    }
    pos += width;
    return value;
  }
  std::uint8_t u8(const std::string& what) { return static_cast<std::uint8_t>(uint(1, what)); }
  std::uint16_t u16(const std::string& what) { return static_cast<std::uint16_t>(uint(2, what)); }
  std::uint32_t u32(const std::string& what) { return static_cast<std::uint32_t>(uint(4, what)); }
  // "Doubles are IEEE 754 64-bit floating-point numbers, and Floats are IEEE
  // 754 32-bit floating-point numbers."
  double f64(const std::string& what) {
    const std::uint64_t bits = uint(8, what);
    double value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }
  float f32(const std::string& what) {
    const std::uint32_t bits = u32(what);
    float value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }
  std::array<double, 3> vec3(const std::string& what) {
    std::array<double, 3> out;
    for (double& c : out)
      c = f64(what);
    return out;
  }
};

// "VertexData": zigZagDecode(value) = (value >> 1) ^ (-(value & 1)).
inline std::int32_t zig_zag_decode(std::uint16_t value) {
  return static_cast<std::int32_t>(value >> 1) ^ -static_cast<std::int32_t>(value & 1);
}

inline std::vector<std::uint32_t> read_index_list(Cursor& in, std::size_t count, bool is32,
                                                  std::uint32_t vertex_count,
                                                  const std::string& what) {
  in.need(count * (is32 ? 4 : 2), what);
  std::vector<std::uint32_t> out(count);
  for (std::size_t i = 0; i < count; ++i) {
    out[i] = is32 ? in.u32(what) : in.u16(what);
    if (out[i] >= vertex_count) {
      fail(what + "[" + std::to_string(i) + "] = " + std::to_string(out[i]) +
           " is not below the vertex count " + std::to_string(vertex_count));
    }
  }
  return out;
}

}  // namespace detail

// Extension 1 "Oct-Encoded Per-Vertex Normals": Cigolle et al. 2014 octahedral
// decoding. Each byte maps 0..255 linearly onto -1..1 (as CesiumJS does, the
// README leaves this implicit); with z = 1 - |x| - |y|, the lower hemisphere
// (z < 0) is unfolded by (x, y) = ((1 - |y|) * sign(x), (1 - |x|) * sign(y))
// where sign(0) = +1; the result is normalised.
inline std::array<double, 3> oct_decode(std::uint8_t byte_x, std::uint8_t byte_y) {
  double x = byte_x / 255.0 * 2.0 - 1.0;
  double y = byte_y / 255.0 * 2.0 - 1.0;
  const double z = 1.0 - std::abs(x) - std::abs(y);
  if (z < 0.0) {
    const double old_x = x;
    x = (1.0 - std::abs(y)) * (old_x >= 0.0 ? 1.0 : -1.0);
    y = (1.0 - std::abs(old_x)) * (y >= 0.0 ? 1.0 : -1.0);
  }
  const double length = std::sqrt(x * x + y * y + z * z);
  return {x / length, y / length, z / length};
}

// Decodes a whole tile. Throws for truncation anywhere, quantized values that
// leave 0..32767, a high-water-mark code above the current high-water mark,
// any index >= vertexCount, malformed extensions (normals not 2 bytes per
// vertex, water mask not 1 or 65536 bytes, metadata jsonLength not filling the
// extension, an extension id repeated), and bytes too few to be an extension.
inline Mesh decode(std::string_view input) {
  using detail::fail;
  std::string inflated;
  if (input.size() >= 2 && static_cast<unsigned char>(input[0]) == 0x1f &&
      static_cast<unsigned char>(input[1]) == 0x8b) {
    inflated = detail::gunzip(input);
    input = inflated;
  }
  detail::Cursor in{input};
  Mesh mesh;

  // "QuantizedMeshHeader".
  if (input.size() < kHeaderSize) {
    fail("tile is " + std::to_string(input.size()) + " bytes, shorter than the 88-byte header");
  }
  mesh.header.center = in.vec3("header center");
  mesh.header.min_height = in.f32("header minimum height");
  mesh.header.max_height = in.f32("header maximum height");
  mesh.header.bounding_sphere_center = in.vec3("header bounding sphere center");
  mesh.header.bounding_sphere_radius = in.f64("header bounding sphere radius");
  mesh.header.horizon_occlusion_point = in.vec3("header horizon occlusion point");

  // "VertexData": three arrays of zig-zag encoded deltas from the previous value.
  const std::uint32_t vertex_count = in.u32("vertexCount");
  in.need(std::size_t{vertex_count} * 6,
          "vertex data (" + std::to_string(vertex_count) + " vertices)");
  const char* names[3] = {"u", "v", "height"};
  std::vector<std::uint16_t>* arrays[3] = {&mesh.u, &mesh.v, &mesh.height};
  for (int a = 0; a < 3; ++a) {
    std::vector<std::uint16_t>& out = *arrays[a];
    out.resize(vertex_count);
    std::int32_t value = 0;
    for (std::uint32_t i = 0; i < vertex_count; ++i) {
      const std::size_t at = in.pos;
      value += detail::zig_zag_decode(in.u16(names[a]));
      if (value < 0 || value > kQuantizedMax) {
        fail("vertex " + std::to_string(i) + ": decoded " + names[a] + " = " +
             std::to_string(value) + " is outside 0..32767 (delta at byte " + std::to_string(at) +
             ")");
      }
      out[i] = static_cast<std::uint16_t>(value);
    }
  }

  // "IndexData16" / "IndexData32", after padding to 2- / 4-byte alignment.
  mesh.indices_are_32bit = vertex_count > kMax16BitVertices;
  const std::size_t index_size = mesh.indices_are_32bit ? 4 : 2;
  if (in.pos % index_size != 0) {
    mesh.index_padding_bytes = index_size - in.pos % index_size;
    in.need(mesh.index_padding_bytes, "padding before the index data");
    in.pos += mesh.index_padding_bytes;
  }
  const std::uint32_t triangle_count = in.u32("triangleCount");
  const std::size_t index_count = std::size_t{triangle_count} * 3;
  in.need(index_count * index_size,
          "triangle indices (" + std::to_string(triangle_count) + " triangles)");
  mesh.triangles.resize(index_count);
  // High-water-mark decoding: index = highest - code; a code of 0 introduces a
  // new vertex and raises the mark. The arithmetic is not wrapped to 16 bits:
  // with exactly 65536 vertices (still IndexData16) a code can then not reach
  // back to vertex 0 once all vertices are introduced -- a limit of the format.
  std::uint32_t highest = 0;
  for (std::size_t i = 0; i < index_count; ++i) {
    const std::size_t at = in.pos;
    const std::uint32_t code = mesh.indices_are_32bit ? in.u32("index") : in.u16("index");
    if (code > highest) {
      fail("triangle index " + std::to_string(i) + ": high-water-mark code " +
           std::to_string(code) + " at byte " + std::to_string(at) +
           " exceeds the current high-water mark " + std::to_string(highest));
    }
    const std::uint32_t index = highest - code;
    if (index >= vertex_count) {
      fail("triangle index " + std::to_string(i) + " decodes to " + std::to_string(index) +
           ", not below the vertex count " + std::to_string(vertex_count));
    }
    mesh.triangles[i] = index;
    if (code == 0) ++highest;
  }

  // "EdgeIndices16" / "EdgeIndices32": west, south, east, north; plain indices.
  std::vector<std::uint32_t>* edges[4] = {&mesh.west_indices, &mesh.south_indices,
                                          &mesh.east_indices, &mesh.north_indices};
  const char* edge_names[4] = {"westIndices", "southIndices", "eastIndices", "northIndices"};
  for (int e = 0; e < 4; ++e) {
    const std::uint32_t count = in.u32(std::string(edge_names[e]) + " count");
    *edges[e] =
        detail::read_index_list(in, count, mesh.indices_are_32bit, vertex_count, edge_names[e]);
  }

  // "Extensions": {unsigned char extensionId; unsigned int extensionLength;} + data.
  while (in.pos < input.size()) {
    const std::size_t at = in.pos;
    if (input.size() - at < 5) {
      fail(std::to_string(input.size() - at) + " trailing bytes at byte " + std::to_string(at) +
           ", too few for an extension header (5 bytes)");
    }
    Extension ext;
    ext.id = in.u8("extension id");
    const std::uint32_t length = in.u32("extension length");
    const std::string what =
        "extension " + std::to_string(ext.id) + " at byte " + std::to_string(at);
    in.need(length, what + " data");
    ext.data = std::string(input.substr(in.pos, length));
    in.pos += length;
    if (mesh.has_extension(ext.id)) fail(what + ": extension id appears twice");

    if (ext.id == 1) {
      // Oct-encoded normals: unsigned char xy[vertexCount * 2].
      if (length != std::size_t{vertex_count} * 2) {
        fail(what + " (oct-encoded normals): length " + std::to_string(length) + ", expected " +
             std::to_string(std::size_t{vertex_count} * 2) + " (2 bytes per vertex)");
      }
      mesh.oct_normals.assign(ext.data.begin(), ext.data.end());
      mesh.normals.reserve(vertex_count);
      for (std::uint32_t i = 0; i < vertex_count; ++i) {
        mesh.normals.push_back(oct_decode(mesh.oct_normals[2 * i], mesh.oct_normals[2 * i + 1]));
      }
    } else if (ext.id == 2) {
      // Water mask: 1 byte, or 256 * 256 bytes.
      if (length != 1 && length != kWaterMaskGridSize * kWaterMaskGridSize) {
        fail(what + " (water mask): length " + std::to_string(length) + ", expected 1 or 65536");
      }
      mesh.water_mask.emplace(ext.data.begin(), ext.data.end());
    } else if (ext.id == 4) {
      // Metadata: unsigned int jsonLength; char json[jsonLength].
      if (length < 4) fail(what + " (metadata): length " + std::to_string(length) + " < 4");
      detail::Cursor meta{ext.data};
      const std::uint32_t json_length = meta.u32("metadata jsonLength");
      if (json_length != length - 4) {
        fail(what + " (metadata): jsonLength " + std::to_string(json_length) +
             " does not match the extension length " + std::to_string(length) + " - 4");
      }
      mesh.metadata_json = ext.data.substr(4);
    }
    mesh.extensions.push_back(std::move(ext));
  }
  return mesh;
}

// Checks the meaning of the edge lists and the winding, which decode() does not:
//  * "EdgeIndices": west vertices have u = 0, south v = 0, east u = 32767,
//    north v = 32767, and every vertex on an edge is listed on that edge;
//  * "IndexData": triangles are counter-clockwise, i.e. positive signed area
//    in the (u east, v north) plane. Zero-area triangles are tolerated.
inline void validate_mesh(const Mesh& mesh) {
  using detail::fail;
  struct Edge {
    const char* name;
    const std::vector<std::uint32_t>* list;
    const std::vector<std::uint16_t>* coordinate;
    int value;
  };
  const Edge edges[4] = {{"west", &mesh.west_indices, &mesh.u, 0},
                         {"south", &mesh.south_indices, &mesh.v, 0},
                         {"east", &mesh.east_indices, &mesh.u, kQuantizedMax},
                         {"north", &mesh.north_indices, &mesh.v, kQuantizedMax}};
  for (const Edge& edge : edges) {
    std::vector<bool> listed(mesh.vertex_count(), false);
    for (std::uint32_t index : *edge.list) {
      if ((*edge.coordinate)[index] != edge.value) {
        fail(std::string(edge.name) + " edge lists vertex " + std::to_string(index) +
             " whose coordinate is " + std::to_string((*edge.coordinate)[index]) + ", not " +
             std::to_string(edge.value));
      }
      listed[index] = true;
    }
    for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
      if ((*edge.coordinate)[i] == edge.value && !listed[i]) {
        fail("vertex " + std::to_string(i) + " lies on the " + edge.name +
             " edge but is missing from its edge list");
      }
    }
  }
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const std::uint32_t a = mesh.triangles[3 * t], b = mesh.triangles[3 * t + 1],
                        c = mesh.triangles[3 * t + 2];
    const std::int64_t area2 =
        (std::int64_t{mesh.u[b]} - mesh.u[a]) * (std::int64_t{mesh.v[c]} - mesh.v[a]) -
        (std::int64_t{mesh.v[b]} - mesh.v[a]) * (std::int64_t{mesh.u[c]} - mesh.u[a]);
    if (area2 < 0) {
      fail("triangle " + std::to_string(t) + " (" + std::to_string(a) + ", " + std::to_string(b) +
           ", " + std::to_string(c) + ") is clockwise; the spec requires counter-clockwise");
    }
  }
}

// ---------------------------------------------------------------------------
// Geometry helpers.

// WGS84 ellipsoid: a = 6378137 m, f = 1 / 298.257223563.
constexpr double kWgs84A = 6378137.0;
constexpr double kWgs84F = 1.0 / 298.257223563;
constexpr double kWgs84E2 = kWgs84F * (2.0 - kWgs84F);  // first eccentricity squared
constexpr double kPi = 3.14159265358979323846;

// Geodetic (degrees, metres above the ellipsoid) -> Earth-centred Earth-fixed
// metres: N = a / sqrt(1 - e^2 sin^2 lat), X = (N + h) cos lat cos lon,
// Y = (N + h) cos lat sin lon, Z = (N (1 - e^2) + h) sin lat.
inline std::array<double, 3> ecef_from_geodetic(double lon_deg, double lat_deg, double height_m) {
  const double lon = lon_deg * kPi / 180.0, lat = lat_deg * kPi / 180.0;
  const double sin_lat = std::sin(lat), cos_lat = std::cos(lat);
  const double n = kWgs84A / std::sqrt(1.0 - kWgs84E2 * sin_lat * sin_lat);
  return {(n + height_m) * cos_lat * std::cos(lon), (n + height_m) * cos_lat * std::sin(lon),
          (n * (1.0 - kWgs84E2) + height_m) * sin_lat};
}

struct Rectangle {
  double west = 0, south = 0, east = 0, north = 0;  // degrees
};

// "Tiling Scheme and Coordinate System": the default EPSG:4326 global-geodetic
// pyramid has 2 x 1 tiles at zoom 0, each 180 degrees wide; with the default
// `tms` scheme y counts from the south, with `slippyMap` from the north.
inline Rectangle geographic_tile_rectangle(int z, std::uint32_t x, std::uint32_t y,
                                           bool tms = true) {
  const double size = 180.0 / std::ldexp(1.0, z);
  Rectangle r;
  r.west = -180.0 + x * size;
  r.east = r.west + size;
  if (tms) {
    r.south = -90.0 + y * size;
    r.north = r.south + size;
  } else {
    r.north = 90.0 - y * size;
    r.south = r.north - size;
  }
  return r;
}

struct Position {
  double lon_deg = 0, lat_deg = 0, height_m = 0;
  std::array<double, 3> ecef() const { return ecef_from_geodetic(lon_deg, lat_deg, height_m); }
};

// "VertexData" table: u, v and height interpolate linearly between the tile's
// west/east longitudes, south/north latitudes and min/max heights, with 0 and
// 32767 at the ends.
inline Position decode_position(const Rectangle& tile, std::uint16_t u, std::uint16_t v,
                                std::uint16_t h, double min_height, double max_height) {
  Position p;
  p.lon_deg = tile.west + (tile.east - tile.west) * (u / double(kQuantizedMax));
  p.lat_deg = tile.south + (tile.north - tile.south) * (v / double(kQuantizedMax));
  p.height_m = min_height + (max_height - min_height) * (h / double(kQuantizedMax));
  return p;
}

inline Position decode_position(const Rectangle& tile, const Mesh& mesh, std::size_t vertex) {
  return decode_position(tile, mesh.u.at(vertex), mesh.v.at(vertex), mesh.height.at(vertex),
                         mesh.header.min_height, mesh.header.max_height);
}

}  // namespace spec_readers::quantized_mesh
