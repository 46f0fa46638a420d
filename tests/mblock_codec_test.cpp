// MBlock codec: exact round trips, rejection of malformed input (every
// truncated prefix, trailing bytes, unknown version/kind), and a frozen
// version-1 golden blob that must keep decoding.
#include <gtest/gtest.h>

#include <fstream>
#include <random>

#include "golden_block.hpp"
#include "test_paths.hpp"
#include "tileformat/blob_header.hpp"
#include "tileformat/error.hpp"
#include "tileformat/kpatch.hpp"
#include "tileformat/mblock.hpp"

using tileformat::decode_mblock;
using tileformat::encode_mblock;
using tileformat::FormatError;
using tileformat::MBlock;

namespace {

MBlock random_block(int size, unsigned seed, bool with_mask, int32_t amplitude) {
  std::mt19937 rng(seed);
  MBlock b;
  b.size = size;
  b.lattice = 16;
  b.step = 0.25;
  b.q.resize(size_t(size) * size);
  std::uniform_int_distribution<int32_t> noise(-amplitude, amplitude);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      b.q[size_t(y) * size + x] = 1000 + 3 * x - 2 * y + noise(rng);
  if (with_mask) {
    b.valid.resize(b.q.size());
    for (auto& v : b.valid)
      v = rng() % 5 != 0;
  }
  b.vertex_error.resize(tileformat::kpatch_vertex_count(tileformat::kpatch_depth(size - 1, 16)));
  for (auto& e : b.vertex_error)
    e = rng() % 1000;
  return b;
}

void expect_same(const MBlock& a, const MBlock& b) {
  EXPECT_EQ(a.size, b.size);
  EXPECT_EQ(a.lattice, b.lattice);
  EXPECT_EQ(a.step, b.step);
  EXPECT_EQ(a.q, b.q);
  EXPECT_EQ(a.valid, b.valid);
  EXPECT_EQ(a.vertex_error, b.vertex_error);
}

}  // namespace

TEST(MBlockCodec, RoundTripsRandomBlocks) {
  for (int size : {33, 65, 257})
    for (bool mask : {false, true})
      for (int32_t amp : {0, 5, 70000, 100000000}) {
        const MBlock b = random_block(size, size * 7 + amp, mask, amp);
        expect_same(decode_mblock(encode_mblock(b)), b);
      }
}

TEST(MBlockCodec, RoundTripsExtremeHeights) {
  MBlock b = random_block(33, 1, false, 0);
  for (size_t i = 0; i < b.q.size(); ++i)
    b.q[i] = (i % 2) ? tileformat::kMaxQuantum : -tileformat::kMaxQuantum;
  expect_same(decode_mblock(encode_mblock(b)), b);
}

TEST(MBlockCodec, RejectsHeightsOutsideTheGrid) {
  MBlock b = random_block(33, 2, false, 0);
  b.q[5] = tileformat::kMaxQuantum + 1;
  EXPECT_THROW(encode_mblock(b), std::invalid_argument);
}

TEST(MBlockCodec, RejectsEveryTruncatedPrefix) {
  const auto blob = encode_mblock(random_block(65, 3, true, 50));
  for (size_t n = 0; n < blob.size(); ++n) {
    std::span<const uint8_t> prefix(blob.data(), n);
    EXPECT_THROW(decode_mblock(prefix), FormatError) << "prefix of " << n << " bytes";
  }
}

TEST(MBlockCodec, RejectsTrailingBytes) {
  auto blob = encode_mblock(random_block(33, 4, false, 10));
  blob.push_back(0);
  try {
    decode_mblock(blob);
    FAIL() << "trailing byte accepted";
  } catch (const FormatError& e) {
    EXPECT_EQ(e.section(), "4");
    EXPECT_NE(std::string(e.what()).find("trailing"), std::string::npos);
  }
}

TEST(MBlockCodec, RejectsNewerVersionsAndOtherKinds) {
  auto blob = encode_mblock(random_block(33, 5, false, 10));
  auto newer = blob;
  newer[4] = 2;  // version (little-endian u16 at offset 4)
  EXPECT_THROW(decode_mblock(newer), FormatError);
  auto other = blob;
  other[6] = 3;  // kind: line clusters
  EXPECT_THROW(decode_mblock(other), FormatError);
  auto garbage = blob;
  garbage[0] = 'X';
  EXPECT_THROW(decode_mblock(garbage), FormatError);
}

TEST(MBlockCodec, RejectsCorruptPayloadWithoutCrashing) {
  const auto blob = encode_mblock(random_block(65, 6, true, 1000));
  std::mt19937 rng(6);
  for (int trial = 0; trial < 300; ++trial) {
    auto bad = blob;
    for (int k = 0; k < 3; ++k)
      bad[tileformat::kBlobHeaderSize + rng() % (bad.size() - tileformat::kBlobHeaderSize)] ^=
          static_cast<uint8_t>(1 + rng() % 255);
    try {
      decode_mblock(bad);  // may decode (a flipped bit in a height) or throw FormatError
    } catch (const FormatError&) {
    }
  }
}

TEST(MBlockCodec, GoldenVersion1BlobStillDecodes) {
  std::ifstream in(globe_test::paths::test_data_dir() + "/golden_mblock_v1.bin", std::ios::binary);
  ASSERT_TRUE(in) << "tests/data/golden_mblock_v1.bin is missing";
  std::vector<uint8_t> blob((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  expect_same(decode_mblock(blob), golden_block());
}

// Builders' scratch grids: any size, both codings, with and without holes,
// round trip exactly; every truncated prefix is rejected.
TEST(HeightGrid, RoundTripsAnySizeAndRejectsTruncation) {
  using tileformat::HeightCoding;
  for (int size : {1, 2, 129, 257})
    for (HeightCoding coding : {HeightCoding::kBytePlanes, HeightCoding::kBestPacking})
      for (bool holes : {false, true}) {
        const MBlock m = random_block(std::max(size, 33), 7u + size, holes, size == 129 ? 3 : 900);
        tileformat::HeightGrid g{size, std::vector<int32_t>(m.q.begin(), m.q.begin() + size * size),
                                 std::vector<uint8_t>(size_t(size) * size, 1)};
        if (holes)
          for (size_t i = 0; i < g.valid.size(); i += 3)
            g.valid[i] = 0;
        const auto bytes = tileformat::encode_height_grid(g, 1, coding);
        const tileformat::HeightGrid back = tileformat::decode_height_grid(bytes);
        EXPECT_EQ(back.size, size);
        EXPECT_EQ(back.q, g.q);
        EXPECT_EQ(back.valid, g.valid);
        for (size_t n = 0; n < bytes.size(); n += std::max<size_t>(1, bytes.size() / 50))
          EXPECT_THROW(tileformat::decode_height_grid({bytes.data(), n}), FormatError) << n;
      }
}
