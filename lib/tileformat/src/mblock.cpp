// MBlock codec (docs/tileformat.md §5): global-grid quantized heights ->
// 2D (Lorenzo) predictor residuals -> zigzag -> byte planes -> zstd.
#include "tileformat/mblock.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>
#include <string>

#include "tileformat/blob_header.hpp"
#include "tileformat/detail/byte_io.hpp"
#include "tileformat/detail/zstd_codec.hpp"
#include "tileformat/kpatch.hpp"

namespace tileformat {
namespace {

constexpr uint8_t kFlagMask = 1;
constexpr int kMaxSize = 4097;

uint32_t zigzag(int32_t v) {
  return (static_cast<uint32_t>(v) << 1) ^ static_cast<uint32_t>(v >> 31);
}
int32_t unzigzag(uint32_t v) {
  return static_cast<int32_t>(v >> 1) ^ -static_cast<int32_t>(v & 1);
}

// Planar (Lorenzo) prediction from the west, north and north-west neighbours.
int64_t predict(const int32_t* q, int size, int x, int y) {
  const size_t i = static_cast<size_t>(y) * size + x;
  if (y == 0) return x == 0 ? 0 : q[i - 1];
  if (x == 0) return q[i - size];
  return int64_t{q[i - 1]} + q[i - size] - q[i - size - 1];
}

bool valid_size(int size, int lattice) {
  const int steps = size - 1;
  return size <= kMaxSize && steps > 0 && std::has_single_bit(static_cast<unsigned>(steps)) &&
         lattice > 0 && std::has_single_bit(static_cast<unsigned>(lattice)) && steps >= 2 * lattice;
}

}  // namespace

MBlockStats mblock_stats(const MBlock& block) {
  MBlockStats s{0, 0};
  bool any = false;
  for (size_t i = 0; i < block.q.size(); ++i) {
    if (!block.valid.empty() && !block.valid[i]) continue;
    if (!any) s = {block.q[i], block.q[i]};
    s.qmin = std::min(s.qmin, block.q[i]);
    s.qmax = std::max(s.qmax, block.q[i]);
    any = true;
  }
  return s;
}

std::vector<uint8_t> encode_mblock(const MBlock& b, int zstd_level) {
  if (!valid_size(b.size, b.lattice))
    throw std::invalid_argument("mblock: size " + std::to_string(b.size) + " / lattice " +
                                std::to_string(b.lattice) + " is not a valid block shape");
  const size_t n = static_cast<size_t>(b.size) * b.size;
  const int depth = kpatch_depth(b.steps(), b.lattice);
  if (b.q.size() != n || (!b.valid.empty() && b.valid.size() != n) ||
      b.vertex_error.size() != kpatch_vertex_count(depth))
    throw std::invalid_argument("mblock: array sizes do not match the block size");
  if (!(b.step > 0) || !std::isfinite(b.step))
    throw std::invalid_argument("mblock: step must be a positive number");

  uint32_t max_z = 0;
  std::vector<uint32_t> residual(n);
  for (int y = 0; y < b.size; ++y)
    for (int x = 0; x < b.size; ++x) {
      const size_t i = static_cast<size_t>(y) * b.size + x;
      if (b.q[i] > kMaxQuantum || b.q[i] < -kMaxQuantum)
        throw std::invalid_argument("mblock: quantized height out of range; use a larger step");
      residual[i] = zigzag(static_cast<int32_t>(b.q[i] - predict(b.q.data(), b.size, x, y)));
      max_z = std::max(max_z, residual[i]);
    }
  const int planes = std::max(1, static_cast<int>((std::bit_width(max_z) + 7) / 8));
  std::vector<uint8_t> plane_bytes(n * planes);
  for (int p = 0; p < planes; ++p)
    for (size_t i = 0; i < n; ++i)
      plane_bytes[p * n + i] = static_cast<uint8_t>(residual[i] >> (8 * p));

  const MBlockStats stats = mblock_stats(b);
  detail::ByteWriter w;
  w.u16(static_cast<uint16_t>(b.size));
  w.u8(static_cast<uint8_t>(b.lattice));
  w.u8(b.valid.empty() ? 0 : kFlagMask);
  w.f64(b.step);
  w.i32(stats.qmin);
  w.i32(stats.qmax);
  w.u8(static_cast<uint8_t>(planes));
  auto heights = detail::zstd_compress(plane_bytes, zstd_level);
  w.u32(static_cast<uint32_t>(heights.size()));
  w.bytes(heights);
  if (!b.valid.empty()) {
    std::vector<uint8_t> bits((n + 7) / 8, 0);
    for (size_t i = 0; i < n; ++i)
      if (b.valid[i]) bits[i / 8] |= static_cast<uint8_t>(1u << (i % 8));
    auto mask = detail::zstd_compress(bits, zstd_level);
    w.u32(static_cast<uint32_t>(mask.size()));
    w.bytes(mask);
  }
  w.u8(static_cast<uint8_t>(depth));
  std::vector<uint8_t> err_bytes;
  detail::ByteWriter ew;
  for (uint32_t e : b.vertex_error)
    ew.u32(e);
  auto errors = detail::zstd_compress(ew.take(), zstd_level);
  w.u32(static_cast<uint32_t>(errors.size()));
  w.bytes(errors);
  auto body = w.take();
  return wrap_blob(BlobKind::kMBlock, body);
}

MBlock decode_mblock(std::span<const uint8_t> blob) {
  auto body = read_blob_header(blob, BlobKind::kMBlock);
  detail::ByteReader r(body, "MBlock header", "5.1");
  MBlock b;
  b.size = r.u16();
  b.lattice = r.u8();
  const uint8_t flags = r.u8();
  b.step = r.f64();
  const int32_t qmin = r.i32(), qmax = r.i32();
  const int planes = r.u8();
  if (!valid_size(b.size, b.lattice))
    r.fail("invalid block shape: size " + std::to_string(b.size) + ", lattice " +
           std::to_string(b.lattice));
  if (flags & ~kFlagMask) r.fail("unknown flags " + std::to_string(flags));
  if (!(b.step > 0) || !std::isfinite(b.step)) r.fail("height step must be positive and finite");
  if (qmin > qmax || qmin < -kMaxQuantum || qmax > kMaxQuantum) r.fail("invalid min/max");
  if (planes < 1 || planes > 4) r.fail("invalid byte-plane count " + std::to_string(planes));

  const size_t n = static_cast<size_t>(b.size) * b.size;
  r.set_section("5.2");
  auto plane_bytes = detail::zstd_decompress(r.bytes(r.u32()), n * planes, "MBlock heights", "5.2");
  b.q.resize(n);
  for (int y = 0; y < b.size; ++y)
    for (int x = 0; x < b.size; ++x) {
      const size_t i = static_cast<size_t>(y) * b.size + x;
      uint32_t z = 0;
      for (int p = 0; p < planes; ++p)
        z |= uint32_t{plane_bytes[p * n + i]} << (8 * p);
      const int64_t v = predict(b.q.data(), b.size, x, y) + unzigzag(z);
      if (v > kMaxQuantum || v < -kMaxQuantum)
        r.fail("height out of range at sample " + std::to_string(i));
      b.q[i] = static_cast<int32_t>(v);
    }
  if (flags & kFlagMask) {
    r.set_section("5.3");
    auto bits = detail::zstd_decompress(r.bytes(r.u32()), (n + 7) / 8, "MBlock mask", "5.3");
    b.valid.resize(n);
    for (size_t i = 0; i < n; ++i)
      b.valid[i] = (bits[i / 8] >> (i % 8)) & 1;
  }
  r.set_section("5.4");
  const int depth = r.u8();
  if (depth != kpatch_depth(b.steps(), b.lattice))
    r.fail("error tree depth " + std::to_string(depth) + " does not match the block shape");
  const size_t count = kpatch_vertex_count(depth);
  auto err_bytes = detail::zstd_decompress(r.bytes(r.u32()), count * 4, "MBlock error tree", "5.4");
  detail::ByteReader er(err_bytes, "MBlock error tree", "5.4");
  b.vertex_error.resize(count);
  for (auto& e : b.vertex_error)
    e = er.u32();
  r.expect_end();
  const MBlockStats s = mblock_stats(b);
  if (s.qmin != qmin || s.qmax != qmax) r.fail("stored min/max do not match the heights");
  return b;
}

}  // namespace tileformat
