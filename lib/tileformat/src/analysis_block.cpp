// Analysis block codec (see analysis_block.hpp, docs/tileformat.md §9).
#include "tileformat/analysis_block.hpp"

#include <cmath>
#include <stdexcept>

#include "tileformat/blob_header.hpp"
#include "tileformat/byte_io.hpp"
#include "tileformat/error.hpp"
#include "tileformat/zstd_codec.hpp"

namespace tileformat {

const std::vector<AnalysisLayerInfo>& analysis_layers() {
  static const std::vector<AnalysisLayerInfo> layers{
      {AnalysisLayer::kSlope, "slope", "degrees", 0.01, 0},
      {AnalysisLayer::kAspect, "aspect", "degrees", 0.01, 0},
      {AnalysisLayer::kProfileCurvature, "profile_curvature", "1/m", 1e-6, -0.032767},
      {AnalysisLayer::kPlanCurvature, "plan_curvature", "1/m", 1e-6, -0.032767},
      {AnalysisLayer::kSkyview, "skyview", "fraction", 1e-4, 0},
      {AnalysisLayer::kFlowDirection, "flow_direction", "D8 code", 1, 0},
      // 2^-15 .. 2^50.5 m^2 (past the Earth's area) at 0.035 % steps.
      {AnalysisLayer::kFlowAccumulation, "flow_accumulation", "m2", 1e-3, -15, true}};
  return layers;
}

const AnalysisLayerInfo& analysis_layer_info(AnalysisLayer layer) {
  for (const AnalysisLayerInfo& i : analysis_layers())
    if (i.layer == layer) return i;
  throw std::invalid_argument("unknown analysis layer id " + std::to_string(int(layer)));
}

std::optional<AnalysisLayer> analysis_layer_by_name(const std::string& name) {
  for (const AnalysisLayerInfo& i : analysis_layers())
    if (name == i.name) return i.layer;
  return std::nullopt;
}

uint16_t quantize(const AnalysisLayerInfo& info, double value) {
  if (info.log2) value = value > 0 ? std::log2(value) : -1e300;
  const double q = std::round((value - info.offset) / info.scale);
  if (!(q > 0)) return 0;  // also NaN, which callers mark kNoValue before
  return q >= kNoValue - 1 ? uint16_t{kNoValue - 1} : static_cast<uint16_t>(q);
}

namespace {

constexpr const char* kSection = "9";

bool known_layer(uint8_t id) {
  for (const AnalysisLayerInfo& i : analysis_layers())
    if (static_cast<uint8_t>(i.layer) == id) return true;
  return false;
}

// The high bit of a layer id in a block: the layer's values are stored as
// they are, not as residuals. Set for the flow directions, codes with no
// order, where a residual only spreads 9 symbols over 17 and into the high
// byte (42 % larger and twice the zstd time at level 9, on a 4097^2 DEM).
constexpr uint8_t kUnpredicted = 0x80;

bool predicted(AnalysisLayer layer) {
  return layer != AnalysisLayer::kFlowDirection;
}

// With `predict`, residuals against the west neighbour (the north one in the
// first column) modulo 2^16; then a low-byte plane and a high-byte plane.
std::vector<uint8_t> to_planes(const std::vector<uint16_t>& v, int size, bool predict) {
  const size_t n = v.size();
  std::vector<uint8_t> planes(2 * n);
  for (size_t i = 0; i < n; ++i) {
    const size_t x = i % size;
    const uint16_t pred = !predict ? 0 : x ? v[i - 1] : (i >= size_t(size) ? v[i - size] : 0);
    const uint16_t r = static_cast<uint16_t>(v[i] - pred);
    planes[i] = static_cast<uint8_t>(r);
    planes[n + i] = static_cast<uint8_t>(r >> 8);
  }
  return planes;
}

std::vector<uint16_t> from_planes(const std::vector<uint8_t>& planes, int size, bool predict) {
  const size_t n = planes.size() / 2;
  std::vector<uint16_t> v(n);
  for (size_t i = 0; i < n; ++i) {
    const size_t x = i % size;
    const uint16_t pred = !predict ? 0 : x ? v[i - 1] : (i >= size_t(size) ? v[i - size] : 0);
    v[i] = static_cast<uint16_t>(pred + (planes[i] | (planes[n + i] << 8)));
  }
  return v;
}

}  // namespace

std::vector<uint8_t> encode_analysis_block(const AnalysisBlock& b, int zstd_level) {
  if (b.size < 2 || b.size > 4097)
    throw std::invalid_argument("analysis block: size must be 2..4097");
  if (b.layers.empty() || b.layers.size() != b.values.size())
    throw std::invalid_argument("analysis block: one value array per layer, at least one layer");
  const size_t n = size_t(b.size) * b.size;
  ByteWriter w;
  w.u16(static_cast<uint16_t>(b.size));
  w.u8(static_cast<uint8_t>(b.layers.size()));
  for (size_t i = 0; i < b.layers.size(); ++i) {
    if (!known_layer(static_cast<uint8_t>(b.layers[i])) || (i && b.layers[i] <= b.layers[i - 1]))
      throw std::invalid_argument("analysis block: layers must be known, ascending, unique");
    if (b.values[i].size() != n) throw std::invalid_argument("analysis block: values not size^2");
    w.u8(static_cast<uint8_t>(static_cast<uint8_t>(b.layers[i]) |
                              (predicted(b.layers[i]) ? 0 : kUnpredicted)));
  }
  // (The lazy search at the final levels: the same size within 0.03 %,
  // 20-30 % less time; see ZstdSearch.)
  const ZstdSearch search = zstd_level >= 8 ? ZstdSearch::kLazy : ZstdSearch::kLevelDefault;
  for (size_t i = 0; i < b.layers.size(); ++i) {
    const std::vector<uint8_t> z =
        zstd_compress(to_planes(b.values[i], b.size, predicted(b.layers[i])), zstd_level, search);
    w.u32(static_cast<uint32_t>(z.size()));
    w.bytes(z);
  }
  const std::vector<uint8_t> body = w.take();
  return wrap_blob(BlobKind::kAnalysis, body);
}

AnalysisBlock decode_analysis_block(std::span<const uint8_t> blob) {
  ByteReader r(read_blob_header(blob, BlobKind::kAnalysis), "analysis block", kSection);
  AnalysisBlock b;
  b.size = r.u16();
  if (b.size < 2 || b.size > 4097) r.fail("size " + std::to_string(b.size) + " outside 2..4097");
  const int count = r.u8();
  if (count == 0) r.fail("no layers");
  std::vector<bool> predict;
  for (int i = 0; i < count; ++i) {
    const uint8_t byte = r.u8();
    // Blocks written before the high bit existed have it clear on every
    // layer: residuals throughout, as they were written.
    predict.push_back(!(byte & kUnpredicted));
    const uint8_t id = byte & ~kUnpredicted;
    if (!known_layer(id)) r.fail("unknown layer id " + std::to_string(id));
    if (i && id <= static_cast<uint8_t>(b.layers.back()))
      r.fail("layer ids must be ascending and unique");
    b.layers.push_back(static_cast<AnalysisLayer>(id));
  }
  const size_t n = size_t(b.size) * b.size;
  for (int i = 0; i < count; ++i) {
    const uint32_t len = r.u32();
    const auto planes = zstd_decompress(r.bytes(len), 2 * n, "analysis block layer", kSection);
    b.values.push_back(from_planes(planes, b.size, predict[size_t(i)]));
  }
  r.expect_end();
  return b;
}

}  // namespace tileformat
