// Analysis blocks (tileformat §9): exact round trip, quantization, and
// malformed blobs rejected with the section cited.
#include <gtest/gtest.h>

#include <random>

#include "tileformat/analysis_block.hpp"
#include "tileformat/blob_header.hpp"
#include "tileformat/byte_io.hpp"
#include "tileformat/error.hpp"
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

// Layers stored as residuals, and the flow directions stored as they are.
TEST(AnalysisBlock, RoundTripsExactly) {
  for (auto make : {random_block, random_flow_block})
    for (int size : {2, 17, 257}) {
      const AnalysisBlock b = make(size, static_cast<uint32_t>(size));
      const AnalysisBlock d = decode_analysis_block(encode_analysis_block(b));
      EXPECT_EQ(d.size, b.size);
      EXPECT_EQ(d.layers, b.layers);
      EXPECT_EQ(d.values, b.values);
    }
}

// The directions are stored as they are (the layer id's high bit set), the
// accumulation as residuals against the west neighbour: the planes written
// here by hand decompress to exactly those.
TEST(AnalysisBlock, FlowDirectionsAreStoredWithoutResiduals) {
  const int size = 17;
  const size_t n = size_t(size) * size;
  const AnalysisBlock b = random_flow_block(size, 5);
  const std::vector<uint8_t> blob = encode_analysis_block(b);
  ByteReader r(read_blob_header(blob, BlobKind::kAnalysis), "test", "9");
  EXPECT_EQ(r.u16(), size);
  EXPECT_EQ(r.u8(), 2);
  EXPECT_EQ(r.u8(), 6 | 0x80) << "directions: high bit set";
  EXPECT_EQ(r.u8(), 7) << "accumulation: residuals";
  for (size_t layer = 0; layer < 2; ++layer) {
    const uint32_t len = r.u32();
    const std::vector<uint8_t> planes = zstd_decompress(r.bytes(len), 2 * n, "test", "9");
    const std::vector<uint16_t>& v = b.values[layer];
    for (size_t i = 0; i < n; ++i) {
      uint16_t expected = v[i];
      if (layer == 1) {
        const uint16_t west = i % size ? v[i - 1] : i >= size_t(size) ? v[i - size] : 0;
        expected = static_cast<uint16_t>(v[i] - west);
      }
      ASSERT_EQ(planes[i] | (planes[n + i] << 8), expected) << "layer " << layer << " sample " << i;
    }
  }
}

// Blocks written before the high bit existed stored every layer, directions
// included, as residuals; they still decode to their values.
TEST(AnalysisBlock, BlocksWithEveryLayerAsResidualsStillDecode) {
  const int size = 17;
  const size_t n = size_t(size) * size;
  const AnalysisBlock b = random_flow_block(size, 9);
  ByteWriter w;
  w.u16(size);
  w.u8(2);
  w.u8(6);
  w.u8(7);
  for (const std::vector<uint16_t>& v : b.values) {
    std::vector<uint8_t> planes(2 * n);
    for (size_t i = 0; i < n; ++i) {
      const uint16_t west = i % size ? v[i - 1] : i >= size_t(size) ? v[i - size] : 0;
      const uint16_t residual = static_cast<uint16_t>(v[i] - west);
      planes[i] = static_cast<uint8_t>(residual);
      planes[n + i] = static_cast<uint8_t>(residual >> 8);
    }
    const std::vector<uint8_t> z = zstd_compress(planes, 3);
    w.u32(static_cast<uint32_t>(z.size()));
    w.bytes(z);
  }
  const AnalysisBlock d = decode_analysis_block(wrap_blob(BlobKind::kAnalysis, w.take()));
  EXPECT_EQ(d.layers, b.layers);
  EXPECT_EQ(d.values, b.values);
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
  auto unsorted = good;
  std::swap(unsorted[12 + 3], unsorted[12 + 4]);
  expect_error(unsorted, "layers out of order");
  auto trailing = good;
  trailing.push_back(0);
  expect_error(trailing, "trailing byte");
  EXPECT_THROW(encode_analysis_block(AnalysisBlock{}), std::invalid_argument);
}

}  // namespace
