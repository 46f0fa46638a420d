// Analysis blocks (tileformat §9): exact round trip, quantization, and
// malformed blobs rejected with the section cited.
#include <gtest/gtest.h>

#include <random>

#include "tileformat/analysis_block.hpp"
#include "tileformat/error.hpp"

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

TEST(AnalysisBlock, RoundTripsExactly) {
  for (int size : {2, 17, 257}) {
    const AnalysisBlock b = random_block(size, static_cast<uint32_t>(size));
    const AnalysisBlock d = decode_analysis_block(encode_analysis_block(b));
    EXPECT_EQ(d.size, b.size);
    EXPECT_EQ(d.layers, b.layers);
    EXPECT_EQ(d.values, b.values);
  }
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
