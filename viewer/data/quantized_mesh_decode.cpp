// Quantized-mesh-1.0 decoding (see quantized_mesh_decode.hpp), written from
// the specification's README: header, zig-zag delta vertex data, padding,
// high-water-mark indices, edge lists, extensions. Every read goes through
// tileformat::ByteReader (bounds-checked); counts are checked against the
// bytes left before a vector is sized from them.
#include "data/quantized_mesh_decode.hpp"

#include <zlib.h>

#include <bit>
#include <cmath>
#include <cstring>

#include "tileformat/byte_io.hpp"
#include "tileformat/error.hpp"

namespace globe::viewer {
namespace {

constexpr const char* kWhat = "quantized-mesh tile";
constexpr uint32_t kMax16BitVertices = 64 * 1024;  // "IndexData": more -> 32-bit indices

std::string section(const char* heading) {
  return std::string("quantized-mesh ") + heading;
}

[[noreturn]] void fail(const char* heading, const std::string& what) {
  throw tileformat::FormatError(section(heading), std::string(kWhat) + ": " + what);
}

float f32(tileformat::ByteReader& in) {
  return std::bit_cast<float>(in.u32());
}

// A count read from the tile, checked against the bytes left for its items.
uint32_t count(tileformat::ByteReader& in, size_t bytes_per_item, const char* heading,
               const char* what) {
  const uint32_t n = in.u32();
  if (uint64_t{n} * bytes_per_item > in.remaining())
    fail(heading, std::string(what) + " count " + std::to_string(n) + " needs " +
                      std::to_string(uint64_t{n} * bytes_per_item) + " bytes, " +
                      std::to_string(in.remaining()) + " left");
  return n;
}

uint32_t index(tileformat::ByteReader& in, bool wide) {
  return wide ? in.u32() : in.u16();
}

std::vector<uint32_t> edge_list(tileformat::ByteReader& in, bool wide, uint32_t vertices,
                                const char* name) {
  const uint32_t n = count(in, wide ? 4 : 2, "EdgeIndices", name);
  std::vector<uint32_t> out(n);
  for (uint32_t& k : out) {
    k = index(in, wide);
    if (k >= vertices)
      fail("EdgeIndices", std::string(name) + " vertex " + std::to_string(k) +
                              " is not below the vertex count " + std::to_string(vertices));
  }
  return out;
}

}  // namespace

std::vector<uint8_t> gunzip_if_gzipped(std::span<const uint8_t> bytes, size_t max_out) {
  if (bytes.size() < 2 || bytes[0] != 0x1f || bytes[1] != 0x8b) return {bytes.begin(), bytes.end()};
  z_stream z{};
  if (inflateInit2(&z, 16 + MAX_WBITS) != Z_OK) fail("gzip", "cannot start zlib");
  std::vector<uint8_t> out;
  z.next_in = const_cast<Bytef*>(bytes.data());
  z.avail_in = static_cast<uInt>(bytes.size());
  int rc = Z_OK;
  std::string error;
  for (;;) {
    if (out.size() - z.total_out < 1) {  // room for more output
      if (out.size() >= max_out) {
        error = "inflates to more than " + std::to_string(max_out) + " bytes";
        break;
      }
      out.resize(std::min(max_out, std::max<size_t>(out.size() * 2, bytes.size() * 4 + 1024)));
    }
    z.next_out = out.data() + z.total_out;
    z.avail_out = static_cast<uInt>(std::min<size_t>(out.size() - z.total_out, 1u << 30));
    rc = inflate(&z, Z_NO_FLUSH);
    if (rc == Z_STREAM_END) {
      // Concatenated members ("gzip -c a b") are one body.
      if (z.avail_in == 0) break;
      if (z.avail_in < 2 || z.next_in[0] != 0x1f || z.next_in[1] != 0x8b) {
        error = std::to_string(z.avail_in) + " trailing bytes after the gzip stream";
        break;
      }
      const uLong done = z.total_out;
      inflateReset(&z);
      z.total_out = done;
      continue;
    }
    if (rc == Z_BUF_ERROR && z.avail_in == 0) {
      error = "gzip stream truncated";
      break;
    }
    if (rc != Z_OK && rc != Z_BUF_ERROR) {
      error = std::string("broken gzip stream: ") +
              (z.msg ? z.msg : "zlib error " + std::to_string(rc));
      break;
    }
  }
  const size_t size = z.total_out;
  inflateEnd(&z);
  if (!error.empty()) fail("gzip", error);
  out.resize(size);
  return out;
}

QuantizedMesh decode_quantized_mesh(std::span<const uint8_t> raw) {
  const std::vector<uint8_t> body = gunzip_if_gzipped(raw);
  tileformat::ByteReader in(body, kWhat, section("QuantizedMeshHeader"));
  QuantizedMesh m;
  QuantizedMeshHeader& h = m.header;
  for (double& c : h.center)
    c = in.f64();
  h.min_height = f32(in);
  h.max_height = f32(in);
  for (double& c : h.bounding_sphere_center)
    c = in.f64();
  h.bounding_sphere_radius = in.f64();
  for (double& c : h.horizon_occlusion_point)
    c = in.f64();
  if (!std::isfinite(h.min_height) || !std::isfinite(h.max_height))
    fail("QuantizedMeshHeader", "minimum or maximum height is not a finite number");
  if (h.min_height > h.max_height)
    fail("QuantizedMeshHeader", "minimum height " + std::to_string(h.min_height) +
                                    " is above the maximum " + std::to_string(h.max_height));

  in.set_section(section("VertexData"));
  const uint32_t n = count(in, 6, "VertexData", "vertex");
  m.u.resize(n);
  m.v.resize(n);
  m.height.resize(n);
  // Zig-zag deltas; the running sums must stay in 0..32767.
  for (std::vector<uint16_t>* values : {&m.u, &m.v, &m.height}) {
    int32_t value = 0;
    for (uint32_t k = 0; k < n; ++k) {
      const uint32_t z = in.u16();
      value += static_cast<int32_t>(z >> 1) ^ -static_cast<int32_t>(z & 1);
      if (value < 0 || value > kQuantizedMeshMax)
        fail("VertexData", (values == &m.u   ? std::string("u")
                            : values == &m.v ? std::string("v")
                                             : std::string("height")) +
                               " of vertex " + std::to_string(k) + " is " + std::to_string(value) +
                               ", outside 0..32767");
      (*values)[k] = static_cast<uint16_t>(value);
    }
  }

  // "IndexData": aligned to its index size (from the start of the tile).
  const bool wide = n > kMax16BitVertices;
  const size_t align = wide ? 4 : 2;
  if (in.position() % align) in.bytes(align - in.position() % align);
  in.set_section(section("IndexData"));
  const uint32_t triangles = count(in, 3 * (wide ? 4 : 2), "IndexData", "triangle");
  m.triangles.resize(size_t{triangles} * 3);
  uint32_t highest = 0;
  for (size_t k = 0; k < m.triangles.size(); ++k) {
    const uint32_t code = index(in, wide);
    if (code > highest)
      fail("IndexData", "index code " + std::to_string(code) + " at " + std::to_string(k) +
                            " exceeds the high-water mark " + std::to_string(highest));
    const uint32_t vertex = highest - code;
    if (vertex >= n)
      fail("IndexData", "triangle " + std::to_string(k / 3) + " names vertex " +
                            std::to_string(vertex) + " of " + std::to_string(n));
    m.triangles[k] = vertex;
    if (code == 0) ++highest;
  }

  in.set_section(section("EdgeIndices"));
  m.west = edge_list(in, wide, n, "west");
  m.south = edge_list(in, wide, n, "south");
  m.east = edge_list(in, wide, n, "east");
  m.north = edge_list(in, wide, n, "north");

  in.set_section(section("Extensions"));
  while (in.remaining() > 0) {
    const uint8_t id = in.u8();
    const uint32_t length = count(in, 1, "Extensions", "extension length");
    const std::span<const uint8_t> data = in.bytes(length);
    switch (id) {
      case 1:  // "Oct-Encoded Per-Vertex Normals"
        if (length != uint64_t{n} * 2)
          fail("Extensions", "octvertexnormals holds " + std::to_string(length) + " bytes for " +
                                 std::to_string(n) + " vertices");
        m.oct_normals.assign(data.begin(), data.end());
        break;
      case 2:  // "Water Mask": 1 byte, or 256 x 256
        if (length != 1 && length != 256 * 256)
          fail("Extensions",
               "water mask of " + std::to_string(length) + " bytes (1 or 65536 expected)");
        m.water_mask.emplace(data.begin(), data.end());
        break;
      case 4: {  // "Metadata": uint32 JSON length, then the JSON
        tileformat::ByteReader meta(data, kWhat, section("Extensions"));
        const uint32_t json = count(meta, 1, "Extensions", "metadata JSON length");
        const std::span<const uint8_t> text = meta.bytes(json);
        m.metadata_json.emplace(text.begin(), text.end());
        break;
      }
      default:  // unknown: skipped, as the spec asks of clients
        break;
    }
  }
  return m;
}

}  // namespace globe::viewer
