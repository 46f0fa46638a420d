// Analysis block codec (see analysis_block.hpp, docs/tileformat.md §9).
#include "tileformat/analysis_block.hpp"

#include <cmath>
#include <stdexcept>

#include "tileformat/blob_header.hpp"
#include "tileformat/byte_io.hpp"
#include "tileformat/error.hpp"
#include "tileformat/flow_layer_coding.hpp"
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

// How a layer's values are stored: the top two bits of its id in the block.
// Blocks from before these existed have them clear (residuals throughout).
enum Coding : uint8_t {
  kWestResiduals = 0x00,  // residuals against the west neighbour, two byte planes
  kAlongFlow = 0x40,      // flow_accumulation: residuals against its donors' sum
  kAsIs = 0x80,           // the values themselves, two byte planes (older flow_direction)
  kNibbles = 0xC0,        // values 0..14 (15: no value), two to a byte
};
constexpr uint8_t kCodingBits = 0xC0;

// The coding a writer picks. D8 codes have no order (a residual spreads 9
// symbols over 17 and into the high byte), so the directions go as 4-bit
// codes; an upstream area is mostly its donors' areas plus its own, so it
// is predicted from them where the block holds the directions and they form
// no cycle (never, as written by the tiler).
Coding coding_for(const AnalysisBlock& b, size_t layer,
                  const std::optional<flow_coding::AreaPredictor>& areas) {
  if (b.layers[layer] == AnalysisLayer::kFlowDirection)
    return flow_coding::fits_in_nibbles(b.values[layer]) ? kNibbles : kAsIs;
  if (areas && areas->acyclic()) return kAlongFlow;
  return kWestResiduals;
}

// The predictor of the block's upstream areas, where it holds them right
// after the flow directions.
std::optional<flow_coding::AreaPredictor> area_predictor(const AnalysisBlock& b, size_t layer) {
  if (layer == 0 || b.layers[layer] != AnalysisLayer::kFlowAccumulation ||
      b.layers[layer - 1] != AnalysisLayer::kFlowDirection)
    return std::nullopt;
  return std::optional<flow_coding::AreaPredictor>(std::in_place, b.values[layer - 1], b.size);
}

// Residuals (v - predicted) modulo 2^16 as a low-byte plane and a high-byte
// plane, and back.
template <typename Predict>
std::vector<uint8_t> to_planes(const std::vector<uint16_t>& v, Predict predicted) {
  const size_t n = v.size();
  std::vector<uint8_t> planes(2 * n);
  for (size_t i = 0; i < n; ++i) {
    const uint16_t r = static_cast<uint16_t>(v[i] - predicted(i));
    planes[i] = static_cast<uint8_t>(r);
    planes[n + i] = static_cast<uint8_t>(r >> 8);
  }
  return planes;
}
uint16_t residual_at(const std::vector<uint8_t>& planes, size_t i) {
  const size_t n = planes.size() / 2;
  return static_cast<uint16_t>(planes[i] | (planes[n + i] << 8));
}

// The west neighbour's value (the north one's in the first column, 0 for
// the first sample).
uint16_t west(const std::vector<uint16_t>& v, int size, size_t i) {
  return i % size_t(size) ? v[i - 1] : i >= size_t(size) ? v[i - size_t(size)] : 0;
}

// The bytes a layer's zstd frame holds.
std::vector<uint8_t> layer_bytes(const AnalysisBlock& b, size_t layer, Coding coding,
                                 const std::optional<flow_coding::AreaPredictor>& areas,
                                 uint16_t source) {
  const std::vector<uint16_t>& v = b.values[layer];
  switch (coding) {
    case kNibbles:
      return flow_coding::pack_nibbles(v);
    case kAsIs:
      return to_planes(v, [](size_t) { return uint16_t{0}; });
    case kAlongFlow:
      return to_planes(v, [&](size_t i) { return areas->predict(v, i, source); });
    default:
      return to_planes(v, [&](size_t i) { return west(v, b.size, i); });
  }
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
  std::vector<Coding> codings;
  std::vector<std::optional<flow_coding::AreaPredictor>> areas;
  for (size_t i = 0; i < b.layers.size(); ++i) {
    if (!known_layer(static_cast<uint8_t>(b.layers[i])) || (i && b.layers[i] <= b.layers[i - 1]))
      throw std::invalid_argument("analysis block: layers must be known, ascending, unique");
    if (b.values[i].size() != n) throw std::invalid_argument("analysis block: values not size^2");
    areas.push_back(area_predictor(b, i));
    codings.push_back(coding_for(b, i, areas.back()));
    w.u8(static_cast<uint8_t>(static_cast<uint8_t>(b.layers[i]) | codings[i]));
  }
  for (size_t i = 0; i < b.layers.size(); ++i) {
    uint16_t source = 0;
    if (codings[i] == kAlongFlow) {
      source = areas[i]->source_value(b.values[i]);
      w.u16(source);
    }
    // The flow codings leave few and short matches: level 1 stores them
    // within 5 % of level 9 in a sixth of the time. The others at
    // `zstd_level`, searched lazily at the final levels (the same size
    // within 0.03 %, 20-30 % less time; see ZstdSearch).
    const bool flow = codings[i] == kNibbles || codings[i] == kAlongFlow;
    const int level = flow ? 1 : zstd_level;
    const ZstdSearch search = level >= 8 ? ZstdSearch::kLazy : ZstdSearch::kLevelDefault;
    const std::vector<uint8_t> z =
        zstd_compress(layer_bytes(b, i, codings[i], areas[i], source), level, search);
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
  std::vector<Coding> codings;
  for (int i = 0; i < count; ++i) {
    const uint8_t byte = r.u8();
    codings.push_back(static_cast<Coding>(byte & kCodingBits));
    const uint8_t id = byte & ~kCodingBits;
    if (!known_layer(id)) r.fail("unknown layer id " + std::to_string(id));
    if (i && id <= static_cast<uint8_t>(b.layers.back()))
      r.fail("layer ids must be ascending and unique");
    b.layers.push_back(static_cast<AnalysisLayer>(id));
    if (codings.back() == kAlongFlow &&
        (b.layers.back() != AnalysisLayer::kFlowAccumulation || i == 0 ||
         b.layers[size_t(i) - 1] != AnalysisLayer::kFlowDirection))
      r.fail("layer " + std::to_string(id) +
             " predicted along the flow, but it is not flow_accumulation after flow_direction");
  }
  const size_t n = size_t(b.size) * b.size;
  for (size_t i = 0; i < codings.size(); ++i) {
    const uint16_t source = codings[i] == kAlongFlow ? r.u16() : 0;
    const uint32_t len = r.u32();
    const size_t bytes = codings[i] == kNibbles ? (n + 1) / 2 : 2 * n;
    const auto z = zstd_decompress(r.bytes(len), bytes, "analysis block layer", kSection);
    std::vector<uint16_t> v(n);
    switch (codings[i]) {
      case kNibbles:
        v = flow_coding::unpack_nibbles(z, n);
        break;
      case kAsIs:
        for (size_t k = 0; k < n; ++k)
          v[k] = residual_at(z, k);
        break;
      case kAlongFlow: {
        const flow_coding::AreaPredictor areas(b.values[i - 1], b.size);
        const auto order = areas.upstream_first();
        if (!order) r.fail("flow_direction forms a cycle: flow_accumulation cannot be decoded");
        for (uint32_t k : *order)
          v[k] = static_cast<uint16_t>(areas.predict(v, k, source) + residual_at(z, k));
        break;
      }
      default:
        for (size_t k = 0; k < n; ++k)
          v[k] = static_cast<uint16_t>(west(v, b.size, k) + residual_at(z, k));
    }
    b.values.push_back(std::move(v));
  }
  r.expect_end();
  return b;
}

}  // namespace tileformat
