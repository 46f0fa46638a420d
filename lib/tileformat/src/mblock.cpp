// MBlock codec (docs/tileformat.md §5): global-grid quantized heights ->
// 2D (Lorenzo) predictor residuals -> zigzag -> packed 2/4-bit values with
// escapes, or byte planes -> zstd; mask and error tree in their own frames.
#include "tileformat/mblock.hpp"

#include <algorithm>
#include <bit>
#include <climits>
#include <cmath>
#include <stdexcept>
#include <string>

#include "tileformat/blob_header.hpp"
#include "tileformat/byte_io.hpp"
#include "tileformat/kpatch.hpp"
#include "tileformat/zstd_codec.hpp"

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

// Planar (Lorenzo) prediction p = W + N - NW (W on the first row, N in the
// first column, 0 for the first sample); residuals are zigzag-encoded.
// Preconditions: |q| <= kMaxQuantum, so every residual fits an int32.
void predict_residuals(const int32_t* q, int size, uint32_t* out) {
  out[0] = zigzag(q[0]);
  for (int x = 1; x < size; ++x)
    out[x] = zigzag(q[x] - q[x - 1]);
  for (int y = 1; y < size; ++y) {
    const int32_t* row = q + static_cast<size_t>(y) * size;
    const int32_t* up = row - size;
    uint32_t* o = out + static_cast<size_t>(y) * size;
    o[0] = zigzag(row[0] - up[0]);
    for (int x = 1; x < size; ++x)
      o[x] =
          zigzag(static_cast<int32_t>(int64_t{row[x]} - (int64_t{row[x - 1]} + up[x] - up[x - 1])));
  }
}

// Inverse of predict_residuals; false if a height leaves the quantization
// range. Each row is a running sum kept in a register (in 64 bits, so a
// hostile row cannot overflow it) and checked against the range once, at
// its end, before the next row reads it (every decoded block runs this).
// range: the min and max of all heights, if asked for.
bool reconstruct(const uint32_t* residual, int size, int32_t* q, MBlockStats* range = nullptr) {
  const size_t n = static_cast<size_t>(size);
  int64_t all_lo = INT64_MAX, all_hi = INT64_MIN;
  for (size_t y = 0; y < n; ++y) {
    int32_t* row = q + y * n;
    const int32_t* up = y ? row - n : nullptr;
    const uint32_t* r = residual + y * n;
    int64_t acc = (up ? up[0] : 0) + int64_t{unzigzag(r[0])};
    int64_t lo = acc, hi = acc;
    row[0] = static_cast<int32_t>(acc);
    if (up) {
      for (size_t x = 1; x < n; ++x) {
        acc += int64_t{up[x]} - up[x - 1] + unzigzag(r[x]);
        row[x] = static_cast<int32_t>(acc);
        lo = std::min(lo, acc);
        hi = std::max(hi, acc);
      }
    } else {
      for (size_t x = 1; x < n; ++x) {
        acc += unzigzag(r[x]);
        row[x] = static_cast<int32_t>(acc);
        lo = std::min(lo, acc);
        hi = std::max(hi, acc);
      }
    }
    if (lo < -kMaxQuantum || hi > kMaxQuantum) return false;
    all_lo = std::min(all_lo, lo);
    all_hi = std::max(all_hi, hi);
  }
  if (range) *range = {static_cast<int32_t>(all_lo), static_cast<int32_t>(all_hi)};
  return true;
}

bool valid_size(int size, int lattice) {
  const int steps = size - 1;
  return size <= kMaxSize && steps > 0 && std::has_single_bit(static_cast<unsigned>(steps)) &&
         lattice > 0 && std::has_single_bit(static_cast<unsigned>(lattice)) && steps >= 2 * lattice;
}

constexpr int kMaxPackedLevel = 6;

// Byte planes at the final levels (8 and up) search lazily (see ZstdSearch):
// the same size within 0.01 % there; packed residuals stay with the level's
// own search, which keeps them 0.2-0.4 % smaller.
ZstdSearch search(int level) {
  return level >= 8 ? ZstdSearch::kLazy : ZstdSearch::kLevelDefault;
}

void put_u32(std::vector<uint8_t>& out, size_t at, uint32_t v) {
  out[at] = static_cast<uint8_t>(v);
  out[at + 1] = static_cast<uint8_t>(v >> 8);
  out[at + 2] = static_cast<uint8_t>(v >> 16);
  out[at + 3] = static_cast<uint8_t>(v >> 24);
}
uint32_t get_u32(const uint8_t* p) {
  return uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
}

// Packs min(z, 2^W - 1) in W bits, least significant first; the escaped
// samples' z - (2^W - 1) go to `exceptions` (u32 each). Returns the count.
template <int W>
uint32_t pack(const std::vector<uint32_t>& residual, std::vector<uint8_t>& packed,
              std::vector<uint8_t>& exceptions) {
  constexpr uint32_t kEsc = (1u << W) - 1;
  constexpr size_t kPerByte = 8 / W;
  const size_t n = residual.size();
  packed.assign((n + kPerByte - 1) / kPerByte, 0);
  uint32_t count = 0;
  for (size_t i = 0; i < n; ++i)
    count += residual[i] >= kEsc;
  exceptions.resize(size_t{count} * 4);
  size_t e = 0;
  for (size_t b = 0; b < packed.size(); ++b) {
    uint8_t byte = 0;
    const size_t base = b * kPerByte;
    for (size_t k = 0; k < kPerByte && base + k < n; ++k) {
      const uint32_t r = residual[base + k];
      if (r >= kEsc) {
        byte |= static_cast<uint8_t>(kEsc << (W * k));
        put_u32(exceptions, e, r - kEsc);
        e += 4;
      } else {
        byte |= static_cast<uint8_t>(r << (W * k));
      }
    }
    packed[b] = byte;
  }
  return count;
}

// Inverse of pack; false if the exceptions do not match the escapes.
template <int W>
bool unpack(std::span<const uint8_t> packed, std::span<const uint8_t> exceptions,
            std::vector<uint32_t>& residual) {
  constexpr uint32_t kEsc = (1u << W) - 1;
  constexpr size_t kPerByte = 8 / W;
  const size_t n = residual.size();
  size_t e = 0;
  for (size_t b = 0; b < packed.size(); ++b) {
    const uint8_t byte = packed[b];
    const size_t base = b * kPerByte;
    for (size_t k = 0; k < kPerByte && base + k < n; ++k) {
      uint32_t v = (byte >> (W * k)) & kEsc;
      if (v == kEsc) {
        if (e + 4 > exceptions.size()) return false;
        const uint32_t extra = get_u32(exceptions.data() + e);
        if (extra > UINT32_MAX - kEsc) return false;
        v += extra;
        e += 4;
      }
      residual[base + k] = v;
    }
  }
  return e == exceptions.size();
}

// §5.2: residuals as byte planes (coding 0) or packed in w bits (coding w =
// 1, 2, 4) with the value 2^w - 1 escaping to an exception stream. Packing
// helps zstd, whose entropy stage cannot go below one bit per byte: small
// residuals packed 4 per byte let it model them jointly.
// Builds the §5.2 section for one coding (0 = byte planes, else w bits);
// empty if the coding does not suit the data (too many escapes).
std::vector<uint8_t> residual_section(const std::vector<uint32_t>& residual, int coding,
                                      int level) {
  const size_t n = residual.size();
  ByteWriter w;
  w.u8(static_cast<uint8_t>(coding));
  if (coding == 0) {
    uint32_t max_z = 0;
    for (uint32_t r : residual)
      max_z = std::max(max_z, r);
    const int planes = std::max(1, static_cast<int>((std::bit_width(max_z) + 7) / 8));
    std::vector<uint8_t> plane_bytes(n * planes);
    for (int p = 0; p < planes; ++p) {
      uint8_t* out = plane_bytes.data() + p * n;
      for (size_t i = 0; i < n; ++i)
        out[i] = static_cast<uint8_t>(residual[i] >> (8 * p));
    }
    w.u8(static_cast<uint8_t>(planes));
    auto data = zstd_compress(plane_bytes, level, search(level));
    w.u32(static_cast<uint32_t>(data.size()));
    w.bytes(data);
    return w.take();
  }
  std::vector<uint8_t> packed, exceptions;
  const uint32_t count = coding == 1   ? pack<1>(residual, packed, exceptions)
                         : coding == 2 ? pack<2>(residual, packed, exceptions)
                                       : pack<4>(residual, packed, exceptions);
  if (count > n / 8) return {};  // mostly escapes: a wider coding wins
  w.u32(count);
  // Packing has done most of the modelling: above level 6 zstd gains 0.4 %
  // on these streams for 35 % more time (measured on etopo20, a 5' global
  // grid and a synthetic 10 m DEM). Two-bit residuals take only matches of 6
  // bytes (24 residuals) or more: 1.3-2.0 % smaller streams on jacksboro, the
  // 5' grids and the synthetic DEM, in about the same time. Four-bit ones
  // keep the level's own search: it is better on smooth grids, worse on rough
  // ones, and no cheap test told them apart (2026-11-28).
  const int packed_level = std::min(level, kMaxPackedLevel);
  auto main = zstd_compress(packed, packed_level,
                            coding == 2 ? ZstdSearch::kLongMatches : ZstdSearch::kLevelDefault);
  w.u32(static_cast<uint32_t>(main.size()));
  w.bytes(main);
  auto exc = zstd_compress(exceptions, packed_level);
  w.u32(static_cast<uint32_t>(exc.size()));
  w.bytes(exc);
  return w.take();
}

// §5.2: residuals as byte planes (coding 0) or packed in w bits (coding w =
// 2, 4) with the value 2^w - 1 escaping to an exception stream. Packing helps
// zstd, whose entropy stage cannot go below one bit per byte: small residuals
// packed 4 per byte let it model them jointly. The narrowest packing whose
// escapes stay under 10 % wins: against byte planes it is smaller whenever it
// qualifies (a 2 % limit left 1 m-step relief grids in byte planes, 0.7 %
// larger and 25 % slower to compress).
std::vector<uint8_t> encode_residuals(const std::vector<uint32_t>& residual, int level,
                                      HeightCoding height_coding) {
  int coding = 0;
  if (height_coding == HeightCoding::kBestPacking) {
    size_t over3 = 0, over15 = 0;
    for (uint32_t r : residual) {
      over3 += r >= 3;
      over15 += r >= 15;
    }
    const size_t rare = residual.size() / 10;
    coding = over3 <= rare ? 2 : (over15 <= rare ? 4 : 0);
  }
  return residual_section(residual, coding, level);
}

// A thread's residuals while it decodes, kept between blocks so that block
// after block touches no new pages; grids larger than kScratchSamples use
// their own (the scratch keeps its capacity).
constexpr size_t kScratchSamples = size_t{1025} * 1025;
std::vector<uint32_t>& residual_scratch() {
  thread_local std::vector<uint32_t> scratch;
  return scratch;
}

// §5.2 into `residual` (resized).
void decode_residuals(ByteReader& r, size_t n, std::vector<uint32_t>& residual) {
  r.set_section("5.2");
  const int coding = r.u8();
  residual.resize(n);
  if (coding == 0) {
    const int planes = r.u8();
    if (planes < 1 || planes > 4) r.fail("invalid byte-plane count " + std::to_string(planes));
    auto bytes = zstd_decompress(r.bytes(r.u32()), n * planes, "MBlock heights", "5.2");
    const uint8_t* b = bytes.data();
    switch (planes) {  // unrolled per plane count: this loop runs for every scratch block
      case 1:
        for (size_t i = 0; i < n; ++i)
          residual[i] = b[i];
        break;
      case 2:
        for (size_t i = 0; i < n; ++i)
          residual[i] = uint32_t{b[i]} | uint32_t{b[n + i]} << 8;
        break;
      default:
        std::fill(residual.begin(), residual.end(), 0u);
        for (int p = 0; p < planes; ++p) {
          const uint8_t* plane = b + p * n;
          for (size_t i = 0; i < n; ++i)
            residual[i] |= uint32_t{plane[i]} << (8 * p);
        }
    }
    return;
  }
  if (coding != 1 && coding != 2 && coding != 4)
    r.fail("unknown height coding " + std::to_string(coding));
  const uint32_t count = r.u32();
  if (count > n) r.fail("more exceptions than samples");
  const size_t per_byte = 8 / coding;
  auto packed =
      zstd_decompress(r.bytes(r.u32()), (n + per_byte - 1) / per_byte, "MBlock heights", "5.2");
  auto exc_bytes =
      zstd_decompress(r.bytes(r.u32()), size_t{count} * 4, "MBlock height exceptions", "5.2");
  const bool ok = coding == 1   ? unpack<1>(packed, exc_bytes, residual)
                  : coding == 2 ? unpack<2>(packed, exc_bytes, residual)
                                : unpack<4>(packed, exc_bytes, residual);
  if (!ok) r.fail("the exceptions do not match the escaped samples");
}

// Skips §5.2 without decompressing it.
void skip_residuals(ByteReader& r) {
  r.set_section("5.2");
  const int coding = r.u8();
  if (coding == 0) {
    r.u8();
    r.bytes(r.u32());
    return;
  }
  r.u32();
  r.bytes(r.u32());
  r.bytes(r.u32());
}

// §5.4
std::vector<uint8_t> encode_error_tree(int depth, const std::vector<uint32_t>& errors, int level) {
  std::vector<uint8_t> raw(errors.size() * 4);
  for (size_t i = 0; i < errors.size(); ++i)
    put_u32(raw, 4 * i, errors[i]);
  ByteWriter w;
  w.u8(static_cast<uint8_t>(depth));
  auto z = zstd_compress(raw, level);
  w.u32(static_cast<uint32_t>(z.size()));
  w.bytes(z);
  return w.take();
}

}  // namespace

MBlockStats mblock_stats(const MBlock& block) {
  // Branch-free, so the loop vectorizes (every decoded block with a mask
  // checks its stored min/max through this).
  int32_t lo = INT32_MAX, hi = INT32_MIN;
  const int32_t* q = block.q.data();
  const size_t n = block.q.size();
  if (block.valid.empty()) {
    for (size_t i = 0; i < n; ++i) {
      lo = std::min(lo, q[i]);
      hi = std::max(hi, q[i]);
    }
  } else {
    const uint8_t* valid = block.valid.data();
    for (size_t i = 0; i < n; ++i) {
      lo = std::min(lo, valid[i] ? q[i] : INT32_MAX);
      hi = std::max(hi, valid[i] ? q[i] : INT32_MIN);
    }
  }
  return lo > hi ? MBlockStats{0, 0} : MBlockStats{lo, hi};
}

std::vector<uint8_t> encode_mblock(const MBlock& b, int zstd_level, HeightCoding coding) {
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

  for (int32_t v : b.q)
    if (v > kMaxQuantum || v < -kMaxQuantum)
      throw std::invalid_argument("mblock: quantized height out of range; use a larger step");
  std::vector<uint32_t> residual(n);
  predict_residuals(b.q.data(), b.size, residual.data());

  const MBlockStats stats = mblock_stats(b);
  ByteWriter w;
  w.u16(static_cast<uint16_t>(b.size));
  w.u8(static_cast<uint8_t>(b.lattice));
  w.u8(b.valid.empty() ? 0 : kFlagMask);
  w.f64(b.step);
  w.i32(stats.qmin);
  w.i32(stats.qmax);
  w.bytes(encode_residuals(residual, zstd_level, coding));
  if (!b.valid.empty()) {
    std::vector<uint8_t> bits((n + 7) / 8, 0);
    for (size_t i = 0; i < n; ++i)
      if (b.valid[i]) bits[i / 8] |= static_cast<uint8_t>(1u << (i % 8));
    auto mask = zstd_compress(bits, zstd_level);
    w.u32(static_cast<uint32_t>(mask.size()));
    w.bytes(mask);
  }
  w.bytes(encode_error_tree(depth, b.vertex_error, zstd_level));
  auto body = w.take();
  return wrap_blob(BlobKind::kMBlock, body);
}

std::vector<uint8_t> encode_height_grid(const HeightGrid& g, int zstd_level, HeightCoding coding) {
  const size_t n = static_cast<size_t>(g.size) * g.size;
  if (g.size < 1 || g.size > 65535 || g.q.size() != n || g.valid.size() != n)
    throw std::invalid_argument("height grid: array sizes do not match the grid size");
  for (int32_t v : g.q)
    if (v > kMaxQuantum || v < -kMaxQuantum)
      throw std::invalid_argument("height grid: quantized height out of range");
  std::vector<uint32_t> residual(n);
  predict_residuals(g.q.data(), g.size, residual.data());
  const bool all_valid = std::all_of(g.valid.begin(), g.valid.end(), [](uint8_t v) { return v; });
  ByteWriter w;
  w.u16(static_cast<uint16_t>(g.size));
  w.u8(all_valid ? 0 : kFlagMask);
  w.bytes(encode_residuals(residual, zstd_level, coding));
  if (!all_valid) {
    std::vector<uint8_t> bits((n + 7) / 8, 0);
    for (size_t i = 0; i < n; ++i)
      if (g.valid[i]) bits[i / 8] |= static_cast<uint8_t>(1u << (i % 8));
    auto mask = zstd_compress(bits, zstd_level);
    w.u32(static_cast<uint32_t>(mask.size()));
    w.bytes(mask);
  }
  return w.take();
}

HeightGrid decode_height_grid(std::span<const uint8_t> bytes) {
  ByteReader r(bytes, "height grid", "5.2");
  HeightGrid g;
  g.size = r.u16();
  const uint8_t flags = r.u8();
  if (g.size < 1 || (flags & ~kFlagMask)) r.fail("invalid grid header");
  const size_t n = static_cast<size_t>(g.size) * g.size;
  std::vector<uint32_t> local;
  std::vector<uint32_t>& residual = n <= kScratchSamples ? residual_scratch() : local;
  decode_residuals(r, n, residual);
  g.q.resize(n);
  if (!reconstruct(residual.data(), g.size, g.q.data()))
    r.fail("a height is outside the quantization range");
  g.valid.assign(n, 1);
  if (flags & kFlagMask) {
    r.set_section("5.3");
    auto bits = zstd_decompress(r.bytes(r.u32()), (n + 7) / 8, "height grid mask", "5.3");
    for (size_t i = 0; i < n; ++i)
      g.valid[i] = (bits[i / 8] >> (i % 8)) & 1;
  }
  r.expect_end();
  return g;
}

MBlock decode_mblock(std::span<const uint8_t> blob) {
  auto body = read_blob_header(blob, BlobKind::kMBlock);
  ByteReader r(body, "MBlock header", "5.1");
  MBlock b;
  b.size = r.u16();
  b.lattice = r.u8();
  const uint8_t flags = r.u8();
  b.step = r.f64();
  const int32_t qmin = r.i32(), qmax = r.i32();
  if (!valid_size(b.size, b.lattice))
    r.fail("invalid block shape: size " + std::to_string(b.size) + ", lattice " +
           std::to_string(b.lattice));
  if (flags & ~kFlagMask) r.fail("unknown flags " + std::to_string(flags));
  if (!(b.step > 0) || !std::isfinite(b.step)) r.fail("height step must be positive and finite");
  if (qmin > qmax || qmin < -kMaxQuantum || qmax > kMaxQuantum) r.fail("invalid min/max");

  const size_t n = static_cast<size_t>(b.size) * b.size;
  std::vector<uint32_t> local;
  std::vector<uint32_t>& residual = n <= kScratchSamples ? residual_scratch() : local;
  decode_residuals(r, n, residual);
  b.q.resize(n);
  MBlockStats all;  // of every sample: the block's stats where it has no mask
  if (!reconstruct(residual.data(), b.size, b.q.data(), &all))
    r.fail("a height is outside the quantization range");
  if (flags & kFlagMask) {
    r.set_section("5.3");
    auto bits = zstd_decompress(r.bytes(r.u32()), (n + 7) / 8, "MBlock mask", "5.3");
    b.valid.resize(n);
    for (size_t i = 0; i < n; ++i)
      b.valid[i] = (bits[i / 8] >> (i % 8)) & 1;
  }
  r.set_section("5.4");
  const int depth = r.u8();
  if (depth != kpatch_depth(b.steps(), b.lattice))
    r.fail("error tree depth " + std::to_string(depth) + " does not match the block shape");
  const size_t count = kpatch_vertex_count(depth);
  auto err_bytes = zstd_decompress(r.bytes(r.u32()), count * 4, "MBlock error tree", "5.4");
  if (err_bytes.size() != count * 4) r.fail("error tree of the wrong length");
  b.vertex_error.resize(count);
  for (size_t i = 0; i < count; ++i)
    b.vertex_error[i] = get_u32(err_bytes.data() + 4 * i);
  r.expect_end();
  const MBlockStats s = b.valid.empty() ? all : mblock_stats(b);
  if (s.qmin != qmin || s.qmax != qmax) r.fail("stored min/max do not match the heights");
  return b;
}

std::vector<uint8_t> replace_vertex_errors(std::span<const uint8_t> blob,
                                           const std::vector<uint32_t>& errors, int zstd_level) {
  auto body = read_blob_header(blob, BlobKind::kMBlock);
  ByteReader r(body, "MBlock header", "5.1");
  const int size = r.u16();
  const int lattice = r.u8();
  const uint8_t flags = r.u8();
  r.bytes(8 + 4 + 4);  // step, qmin, qmax
  if (!valid_size(size, lattice)) r.fail("invalid block shape");
  skip_residuals(r);
  if (flags & kFlagMask) {
    r.set_section("5.3");
    r.bytes(r.u32());
  }
  const size_t tree_start = r.position();
  const int depth = kpatch_depth(size - 1, lattice);
  if (errors.size() != kpatch_vertex_count(depth))
    throw std::invalid_argument("mblock: vertex error count does not match the block shape");
  std::vector<uint8_t> out(body.begin(), body.begin() + static_cast<ptrdiff_t>(tree_start));
  auto tree = encode_error_tree(depth, errors, zstd_level);
  out.insert(out.end(), tree.begin(), tree.end());
  return wrap_blob(BlobKind::kMBlock, out);
}

}  // namespace tileformat
