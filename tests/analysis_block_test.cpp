// Analysis blocks (tileformat §9): exact round trip, quantization, and
// malformed blobs rejected with the section cited.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tileformat/analysis_block.hpp"
#include "tileformat/blob_header.hpp"
#include "tileformat/byte_io.hpp"
#include "tileformat/error.hpp"
#include "tileformat/flow_layer_coding.hpp"
#include "tileformat/zstd_codec.hpp"

namespace {

using namespace tileformat;

AnalysisBlock random_block(int size, uint32_t seed) {
  std::mt19937 rng(seed);
  AnalysisBlock b;
  b.size = size;
  b.layers = {AnalysisLayer::kSlope, AnalysisLayer::kAspect, AnalysisLayer::kPlanCurvature};
  for (size_t l = 0; l < b.layers.size(); ++l) {
    std::vector<uint16_t> v(size_t(size) * size);
    for (auto& q : v)
      q = rng() % 7 == 0 ? kNoValue : static_cast<uint16_t>(rng() % 9000);
    b.values.push_back(std::move(v));
  }
  return b;
}

// Flow layers: D8 codes 0..8 and log areas, no value at the edge.
AnalysisBlock random_flow_block(int size, uint32_t seed) {
  std::mt19937 rng(seed);
  AnalysisBlock b;
  b.size = size;
  b.layers = {AnalysisLayer::kFlowDirection, AnalysisLayer::kFlowAccumulation};
  std::vector<uint16_t> code(size_t(size) * size), area(code.size());
  for (size_t i = 0; i < code.size(); ++i) {
    const bool none = i % size_t(size) == 0;
    code[i] = none ? kNoValue : static_cast<uint16_t>(rng() % 9);
    area[i] = none ? kNoValue : static_cast<uint16_t>(15000 + rng() % 20000);
  }
  b.values = {code, area};
  return b;
}

// Flow layers as the tiler writes them: each cell drains to its lowest
// lower neighbour of a random height field (no cycles), or is an outlet.
AnalysisBlock drained_flow_block(int size, uint32_t seed) {
  AnalysisBlock b = random_flow_block(size, seed);
  std::mt19937 rng(seed);
  std::vector<uint32_t> height(size_t(size) * size);
  for (auto& z : height)
    z = rng() % 50;
  const int dx[9] = {0, 0, 1, 1, 1, 0, -1, -1, -1}, dy[9] = {0, -1, -1, 0, 1, 1, 1, 0, -1};
  for (size_t i = 0; i < height.size(); ++i) {
    if (b.values[0][i] == kNoValue) continue;
    const int x = int(i % size_t(size)), y = int(i / size_t(size));
    uint16_t best = 0;
    uint32_t lowest = height[i];
    for (uint16_t d = 1; d <= 8; ++d) {
      const int nx = x + dx[d], ny = y + dy[d];
      if (nx < 0 || ny < 0 || nx >= size || ny >= size) continue;
      if (height[size_t(ny) * size + nx] < lowest)
        best = d, lowest = height[size_t(ny) * size + nx];
    }
    b.values[0][i] = best;
  }
  return b;
}

// Every coding: residuals, directions packed, areas predicted along the
// flow, and areas as residuals where the directions form cycles.
TEST(AnalysisBlock, RoundTripsExactly) {
  for (auto make : {random_block, random_flow_block, drained_flow_block})
    for (int size : {2, 17, 257}) {
      const AnalysisBlock b = make(size, static_cast<uint32_t>(size));
      const AnalysisBlock d = decode_analysis_block(encode_analysis_block(b));
      EXPECT_EQ(d.size, b.size);
      EXPECT_EQ(d.layers, b.layers);
      EXPECT_EQ(d.values, b.values);
    }
}

// A block small enough to predict by hand: four sources (20000, one 20003)
// drain through (1,0) and (1,1) to the outlet (1,2); the bottom corners have
// no data. The gain of adding an area t quanta below is
// round(1000 log2(1 + 2^(-t/1000))): 1000 for t = 0, 585 for 1000, 415 for
// 1586, 322 for 1998, 263 for 2323, 223 for 2584.
TEST(AnalysisBlock, FlowLayersArePackedAndPredictedAlongTheFlow) {
  AnalysisBlock b;
  b.size = 3;
  b.layers = {AnalysisLayer::kFlowDirection, AnalysisLayer::kFlowAccumulation};
  const uint16_t none = kNoValue;
  b.values = {{3, 5, 7, 3, 5, 7, none, 0, none},
              {20000, 21586, 20000, 20000, 22584, 20003, none, 22807, none}};
  const std::vector<uint8_t> blob = encode_analysis_block(b);
  ByteReader r(read_blob_header(blob, BlobKind::kAnalysis), "test", "9");
  EXPECT_EQ(r.u16(), 3);
  EXPECT_EQ(r.u8(), 2);
  EXPECT_EQ(r.u8(), 6 | 0xC0) << "directions: 4-bit codes";
  EXPECT_EQ(r.u8(), 7 | 0x40) << "accumulation: predicted along the flow";
  uint32_t len = r.u32();
  EXPECT_EQ(zstd_decompress(r.bytes(len), 5, "test", "9"),
            (std::vector<uint8_t>{0x53, 0x37, 0x75, 0x0F, 0x0F}));
  EXPECT_EQ(r.u16(), 20000) << "the most common value of the cells without donors";
  len = r.u32();
  // (1,0): 20000 (+) 20000 (+) 20000 = 21585, stored 21586: +1. (1,1): its
  // donors N 21586, E 20003, W 20000 in code order: 20000 (+) 21586 = 22001,
  // (+) 20003 = 22323, (+) 20000 = 22586, stored 22584: -2. (1,2): 20000 (+)
  // 22584 = 22807: 0. The source at 20003: +3.
  const std::vector<uint16_t> residuals{0, 1, 0, 0, 65534, 3, 0, 0, 0};
  std::vector<uint8_t> planes;
  for (int plane = 0; plane < 2; ++plane)
    for (uint16_t v : residuals)
      planes.push_back(static_cast<uint8_t>(plane ? v >> 8 : v & 0xFF));
  EXPECT_EQ(zstd_decompress(r.bytes(len), 18, "test", "9"), planes);
  r.expect_end();
  EXPECT_EQ(decode_analysis_block(blob).values, b.values);
}

// Directions that form a cycle cannot order a prediction: the writer stores
// the areas as residuals against the west neighbour, and a reader rejects a
// block that claims otherwise.
TEST(AnalysisBlock, AreasOverCyclingDirectionsAreStoredAsResiduals) {
  AnalysisBlock b;
  b.size = 2;
  b.layers = {AnalysisLayer::kFlowDirection, AnalysisLayer::kFlowAccumulation};
  b.values = {{3, 7, 0, 0}, {20000, 20500, 20000, 21000}};  // the top two drain into each other
  std::vector<uint8_t> blob = encode_analysis_block(b);
  const size_t ids = 12 + 3;  // blob header, size, count
  EXPECT_EQ(blob[ids + 1], 7) << "accumulation: west residuals";
  EXPECT_EQ(decode_analysis_block(blob).values, b.values);
  // The same block claiming the flow prediction: a u16 source before the frame.
  ByteWriter w;
  w.u16(2);
  w.u8(2);
  w.u8(6 | 0xC0);
  w.u8(7 | 0x40);
  for (const std::vector<uint8_t>& bytes :
       {std::vector<uint8_t>{0x73, 0x00}, std::vector<uint8_t>(8, 0)}) {
    if (bytes.size() == 8) w.u16(20000);
    const std::vector<uint8_t> z = zstd_compress(bytes, 3);
    w.u32(static_cast<uint32_t>(z.size()));
    w.bytes(z);
  }
  try {
    decode_analysis_block(wrap_blob(BlobKind::kAnalysis, w.take()));
    ADD_FAILURE() << "a cycle was accepted";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("cycle"), std::string::npos) << e.what();
  }
}

// Blocks written before the codings existed stored every layer, directions
// included, as residuals against the west neighbour; the next ones stored
// the directions as they are (0x80). Both still decode to their values.
TEST(AnalysisBlock, OlderFlowBlocksStillDecode) {
  const int size = 17;
  const size_t n = size_t(size) * size;
  const AnalysisBlock b = drained_flow_block(size, 9);
  for (const bool directions_as_is : {false, true}) {
    ByteWriter w;
    w.u16(size);
    w.u8(2);
    w.u8(directions_as_is ? 6 | 0x80 : 6);
    w.u8(7);
    for (size_t layer = 0; layer < 2; ++layer) {
      const std::vector<uint16_t>& v = b.values[layer];
      std::vector<uint8_t> planes(2 * n);
      for (size_t i = 0; i < n; ++i) {
        const uint16_t west = i % size ? v[i - 1] : i >= size_t(size) ? v[i - size] : 0;
        const uint16_t stored =
            layer == 0 && directions_as_is ? v[i] : static_cast<uint16_t>(v[i] - west);
        planes[i] = static_cast<uint8_t>(stored);
        planes[n + i] = static_cast<uint8_t>(stored >> 8);
      }
      const std::vector<uint8_t> z = zstd_compress(planes, 3);
      w.u32(static_cast<uint32_t>(z.size()));
      w.bytes(z);
    }
    const AnalysisBlock d = decode_analysis_block(wrap_blob(BlobKind::kAnalysis, w.take()));
    EXPECT_EQ(d.layers, b.layers);
    EXPECT_EQ(d.values, b.values) << (directions_as_is ? "directions as is" : "all residuals");
  }
}

// The gains are built in integers; every one is the exact function rounded
// (computed here in floating point, with a margin where it nears a half).
TEST(AnalysisBlock, LogAddGainsAreTheRoundedLogSum) {
  const std::vector<uint16_t>& gains = flow_coding::log_add_gains();
  for (uint32_t t = 0; t < 13000; ++t) {
    const double exact = 1000 * std::log2(1 + std::exp2(-double(t) / 1000));
    const uint16_t gain = t < gains.size() ? gains[t] : 0;
    if (std::abs(exact - std::floor(exact) - 0.5) < 1e-6) continue;
    ASSERT_EQ(gain, std::lround(exact)) << "t = " << t;
  }
  EXPECT_EQ(gains.size(), 11495u) << "the first gain of 0";
}

TEST(AnalysisBlock, QuantizesToTheStatedPrecision) {
  const AnalysisLayerInfo& slope = analysis_layer_info(AnalysisLayer::kSlope);
  EXPECT_NEAR(dequantize(slope, quantize(slope, 33.3349)), 33.3349, 0.005);
  EXPECT_EQ(quantize(slope, -1), 0);
  const AnalysisLayerInfo& plan = analysis_layer_info(AnalysisLayer::kPlanCurvature);
  EXPECT_NEAR(dequantize(plan, quantize(plan, -0.0123456)), -0.0123456, 5e-7);
  EXPECT_EQ(quantize(plan, 1.0), kNoValue - 1) << "clamped, never the no-value code";
  EXPECT_EQ(analysis_layer_by_name("aspect"), AnalysisLayer::kAspect);
  EXPECT_FALSE(analysis_layer_by_name("wetness"));
}

TEST(AnalysisBlock, MalformedBlobsAreRejected) {
  const std::vector<uint8_t> good = encode_analysis_block(random_block(17, 1));
  auto expect_error = [](std::vector<uint8_t> blob, const std::string& what) {
    try {
      decode_analysis_block(blob);
      ADD_FAILURE() << "accepted: " << what;
    } catch (const FormatError& e) {
      EXPECT_NE(std::string(e.what()).find("§"), std::string::npos) << e.what();
    }
  };
  auto truncated = good;
  truncated.resize(good.size() - 5);
  expect_error(truncated, "truncated");
  auto bad_layer = good;
  bad_layer[12 + 3] = 99;  // first layer id
  expect_error(bad_layer, "unknown layer");
  auto along_flow = good;
  along_flow[12 + 3] |= 0x40;  // slope claiming the flow prediction
  expect_error(along_flow, "flow prediction on another layer");
  auto unsorted = good;
  std::swap(unsorted[12 + 3], unsorted[12 + 4]);
  expect_error(unsorted, "layers out of order");
  auto trailing = good;
  trailing.push_back(0);
  expect_error(trailing, "trailing byte");
  EXPECT_THROW(encode_analysis_block(AnalysisBlock{}), std::invalid_argument);
}

}  // namespace
