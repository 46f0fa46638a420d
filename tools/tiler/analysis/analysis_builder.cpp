// The analysis builder (see analysis_builder.hpp).
#include "analysis_builder.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>

#include "errors.hpp"
#include "package_output.hpp"
#include "parallel_batches.hpp"
#include "terrain_derivatives.hpp"
#include "terrain_package.hpp"
#include "tileformat/error.hpp"
#include "tileformat/mblock.hpp"
#include "tileformat/metadata.hpp"

namespace globe {
namespace {

using tileformat::AnalysisLayer;
using tileformat::TileId;

using Blobs = std::map<TileId, std::shared_ptr<const std::vector<uint8_t>>>;

// The up to 9 tiles whose samples a block's window reads: itself and its
// neighbours (east-west wrapping in the global tilings).
std::vector<TileId> neighbourhood(const tileformat::Tiling& t, TileId id) {
  std::vector<TileId> out;
  const int64_t nx = static_cast<int64_t>(t.tiles_x(id.z)),
                ny = static_cast<int64_t>(t.tiles_y(id.z));
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      int64_t x = int64_t(id.x) + dx, y = int64_t(id.y) + dy;
      if (y < 0 || y >= ny) continue;
      if (x < 0 || x >= nx) {
        if (t.wrap_tiles() == 0) continue;
        x = (x + nx) % nx;
      }
      out.push_back({id.z, uint32_t(x), uint32_t(y)});
    }
  return out;
}

class BlockAnalyzer {
 public:
  BlockAnalyzer(const TerrainPackage& p, const std::vector<AnalysisLayer>& layers,
                const std::string& path)
      : p_(p), layers_(layers), path_(path) {}

  std::vector<uint8_t> analyze(TileId id, const Blobs& blobs) const {
    const int s = p_.block_size, n = s - 1, g = s + 2;  // g: the window with a 1-sample halo
    std::vector<double> h(size_t(g) * g, 0);
    std::vector<uint8_t> ok(size_t(g) * g, 0);
    const int64_t nx = static_cast<int64_t>(p_.tiling.tiles_x(id.z));
    for (const TileId& t : neighbourhood(p_.tiling, id)) {
      const auto it = blobs.find(t);
      if (it == blobs.end() || !it->second) continue;  // no tile there: no data
      const tileformat::MBlock b = decode(t, *it->second);
      // Offset of block t's samples in the window: dx, dy in -1..1 tiles.
      int64_t dx = int64_t(t.x) - int64_t(id.x);
      if (dx > 1) dx -= nx;
      if (dx < -1) dx += nx;
      const int64_t dy = int64_t(t.y) - int64_t(id.y);
      for (int y = 0; y < s; ++y) {
        const int64_t wy = dy * n + y + 1;
        if (wy < 0 || wy >= g) continue;
        for (int x = 0; x < s; ++x) {
          const int64_t wx = dx * n + x + 1;
          if (wx < 0 || wx >= g) continue;
          const size_t k = size_t(wy) * g + size_t(wx);
          if (t == id || !ok[k]) {  // shared edge samples are equal; the block itself wins
            h[k] = b.height(x, y);
            ok[k] = b.is_valid(x, y) ? 1 : 0;
          }
        }
      }
    }
    tileformat::AnalysisBlock out;
    out.size = s;
    out.layers = layers_;
    out.values.assign(layers_.size(), std::vector<uint16_t>(size_t(s) * s, tileformat::kNoValue));
    for (int y = 0; y < s; ++y) {
      const GroundSpacing sp = ground_spacing(p_.tiling, id.z, n, id.y, y);
      for (int x = 0; x < s; ++x) {
        const size_t c = size_t(y + 1) * g + size_t(x + 1);
        if (!ok[c]) continue;
        Window3 w;
        for (int j = 0; j < 3; ++j)
          for (int i = 0; i < 3; ++i) {
            const size_t k = c + size_t(j - 1) * g + size_t(i) - 1;
            w.z[j * 3 + i] = ok[k] ? h[k] : h[c];
          }
        const Derivatives d = derivatives(w, sp.dx, sp.dy);
        for (size_t l = 0; l < layers_.size(); ++l) {
          double v = 0;
          switch (layers_[l]) {
            case AnalysisLayer::kSlope:
              v = d.slope_deg;
              break;
            case AnalysisLayer::kAspect:
              v = d.aspect_deg;
              break;
            case AnalysisLayer::kProfileCurvature:
              v = d.profile;
              break;
            case AnalysisLayer::kPlanCurvature:
              v = d.plan;
              break;
          }
          if (!std::isnan(v))
            out.values[l][size_t(y) * s + x] =
                tileformat::quantize(tileformat::analysis_layer_info(layers_[l]), v);
        }
      }
    }
    return tileformat::encode_analysis_block(out);
  }

 private:
  tileformat::MBlock decode(TileId t, const std::vector<uint8_t>& blob) const {
    try {
      return tileformat::decode_mblock(blob);
    } catch (const tileformat::FormatError& e) {
      throw InputError(path_ + ": tile " + t.str() + ": " + e.what() +
                       "; rebuild the terrain package (globe-tiler validate lists bad tiles)");
    }
  }
  const TerrainPackage& p_;
  const std::vector<AnalysisLayer>& layers_;
  const std::string& path_;
};

tileformat::AnalysisMetadata analysis_metadata(const AnalysisSettings& s, const TerrainPackage& p) {
  tileformat::AnalysisMetadata m;
  m.common = p.meta.common;
  m.common.name = std::filesystem::path(s.output).stem().string();
  m.common.format = tileformat::kAnalysisFormat;
  m.common.type = "overlay";
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(s.inputs[0], ec);
  m.common.inputs = {{s.inputs[0], ec ? 0 : bytes}};
  m.common.description =
      tileformat::build_description("Terrain analysis", "globe-tiler", m.common.inputs);
  m.common.generator = "globe-tiler " GLOBE_VERSION;
  m.common.command_line = s.command_line;
  m.block_size = p.block_size;
  m.layers = s.layers;
  m.terrain = std::filesystem::path(s.inputs[0]).filename().string();
  m.height_step = p.step_m;
  return m;
}

}  // namespace

AnalysisSummary build_analysis(const AnalysisSettings& s, Progress& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::string& path = s.inputs[0];
  TerrainPackage p = open_terrain_package(path);
  std::vector<TileId> items;
  for (int z = p.min_zoom; z <= p.max_zoom; ++z)
    for (const TileId& id : p.reader->tile_ids(z))
      items.push_back(id);
  AnalysisSummary sum;
  try {
    std::unique_ptr<tileformat::PackageWriter> writer = create_package(s, progress);
    // Tiles are written in item order and committed in that order: a
    // resumed build's package holds a prefix of the items.
    size_t first = 0;
    if (writer->resumed())
      for (int z = p.min_zoom; z <= p.max_zoom; ++z)
        first += writer->tiles_at_zoom(z);
    const BlockAnalyzer analyzer(p, s.layers, path);
    progress.begin("analyze", items.size());
    progress.advance(first);
    parallel_batches<Blobs, std::vector<uint8_t>>(
        items.size(), s.worker_threads(), 64,
        [&](size_t begin, size_t end) {
          Blobs blobs;
          for (size_t i = begin; i < end; ++i)
            for (const TileId& t : neighbourhood(p.tiling, items[i]))
              if (!blobs.count(t)) {
                auto blob = p.reader->tile(t);
                blobs[t] =
                    blob ? std::make_shared<const std::vector<uint8_t>>(std::move(*blob)) : nullptr;
              }
          return blobs;
        },
        [&](size_t i, int, const Blobs& blobs) { return analyzer.analyze(items[i], blobs); },
        [&](size_t i, std::vector<uint8_t>&& blob) {
          writer->put_tile(items[i], blob);
          progress.advance();
        },
        [](size_t) {}, first);
    progress.end();
    writer->set_metadata(tileformat::to_metadata(analysis_metadata(s, p)));
    sum.tiles = items.size();
    sum.unique_blobs = writer->unique_blobs();
    sum.file_bytes = commit_package(*writer, s.output);
  } catch (const tileformat::PackageError& e) {
    throw build_write_error(s.output, e);
  }
  sum.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return sum;
}

}  // namespace globe
