// Terrain staged-data codecs (see terrain_stages.hpp).
#include "terrain/terrain_stages.hpp"

#include "tileformat/byte_io.hpp"
#include "tileformat/mblock.hpp"

namespace globe {
namespace {

constexpr int kStageZstdLevel = 1;

}  // namespace

std::vector<uint8_t> encode_scratch(const Block& b, int size) {
  return tileformat::encode_height_grid({size, b.q, b.valid}, kStageZstdLevel,
                                        tileformat::HeightCoding::kBestPacking);
}

Block decode_scratch(std::span<const uint8_t> bytes) {
  tileformat::HeightGrid g = tileformat::decode_height_grid(bytes);
  return Block{std::move(g.q), std::move(g.valid)};
}

std::vector<uint8_t> encode_quarter(const Block& b, int steps) {
  const int size = steps + 1, half = steps / 2 + 1;
  Block qb{std::vector<int32_t>(size_t(half) * half), std::vector<uint8_t>(size_t(half) * half)};
  for (int y = 0; y < half; ++y)
    for (int x = 0; x < half; ++x) {
      const size_t src = size_t(2 * y) * size + 2 * x, dst = size_t(y) * half + x;
      qb.q[dst] = b.q[src];
      qb.valid[dst] = b.valid[src];
    }
  return encode_scratch(qb, half);
}

std::vector<uint8_t> pack_edges(const Block& b, int size) {
  tileformat::ByteWriter w;
  auto put = [&](size_t i) {
    w.i32(b.q[i]);
    w.u8(b.valid[i]);
  };
  for (int x = 0; x < size; ++x)
    put(size_t(x));
  for (int y = 0; y < size; ++y)
    put(size_t(y) * size);
  return w.take();
}

Block unpack_edges(std::span<const uint8_t> bytes, int size) {
  tileformat::ByteReader r(bytes, "staged block edges", "scratch");
  Block e;
  e.q.resize(2 * size_t(size));
  e.valid.resize(2 * size_t(size));
  for (size_t k = 0; k < e.q.size(); ++k) {
    e.q[k] = r.i32();
    e.valid[k] = r.u8();
  }
  r.expect_end();
  return e;
}

std::vector<uint8_t> pack_errors(const std::vector<uint32_t>& errors) {
  tileformat::ByteWriter w;
  for (uint32_t e : errors)
    w.u32(e);
  return w.take();
}

std::vector<uint32_t> unpack_errors(std::span<const uint8_t> bytes) {
  tileformat::ByteReader r(bytes, "staged node errors", "scratch");
  std::vector<uint32_t> out(bytes.size() / 4);
  for (uint32_t& e : out)
    e = r.u32();
  r.expect_end();
  return out;
}

}  // namespace globe
